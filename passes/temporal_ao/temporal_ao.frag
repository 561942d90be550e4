#version 450 core
// Reprojected temporal accumulation of the AO term: each covered pixel is found in last frame
// (through the previous view and projection) and blended with last frame's accumulated AO when
// it shows the same line at the expected depth; otherwise the history is dropped.
#include "fullscreen_pass.glsl"
#include "lineao_common.glsl"

#ifdef FULLSCREEN_COMPUTE
layout(r16f) writeonly uniform image2D u_ao_acc;
void write_ao(ivec2 p, float ao) { imageStore(u_ao_acc, p, vec4(ao)); }
#else
layout(location = 0) out float o_ao;
void write_ao(ivec2 p, float ao) { o_ao = ao; }
#endif
// The pins, by declaration:
uniform sampler2D u_ao;                  // this frame's AO
uniform sampler2D u_ao_prev;             // last frame's accumulated AO
uniform sampler2D u_normal_depth;        // normal (xyz), linear depth (w)
uniform sampler2D u_normal_depth_prev;
uniform isampler2D u_line_id;            // line id, -1 on background
uniform isampler2D u_line_id_prev;
uniform mat4 u_cur_to_prev_view;  // prev_view * inverse(view)
uniform mat4 u_prev_proj;
uniform vec2 u_proj_scale;        // proj[0][0], proj[1][1] (symmetric perspective)
uniform vec2 u_near_far, u_prev_near_far;
uniform float u_alpha;            // weight of this frame (the parameter, by declaration)
uniform float u_depth_tolerance;  // in normalised linear depth (the parameter)
uniform bool u_history_valid;

// This frame's AO blended with last frame's where pixel p shows the same line there.
float accumulated(ivec2 p) {
    float ao = texelFetch(u_ao, p, 0).r;
    int id = texelFetch(u_line_id, p, 0).r;
    vec4 nd = texelFetch(u_normal_depth, p, 0);
    if (!u_history_valid || id < 0 || !nd_is_geometry(nd)) return ao;
    vec2 size = vec2(textureSize(u_ao, 0));
    vec2 ndc = (vec2(p) + 0.5) / size * 2.0 - 1.0;
    float eye = u_near_far.x + nd.w * (u_near_far.y - u_near_far.x);
    vec4 view_pos = vec4(ndc.x * eye / u_proj_scale.x, ndc.y * eye / u_proj_scale.y, -eye, 1.0);
    vec4 prev_view = u_cur_to_prev_view * view_pos;
    vec4 clip = u_prev_proj * prev_view;
    if (clip.w <= 0.0) return ao;
    ivec2 q = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * size));
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(size)))) return ao;
    float expected = (-prev_view.z - u_prev_near_far.x) / (u_prev_near_far.y - u_prev_near_far.x);
    if (texelFetch(u_line_id_prev, q, 0).r != id) return ao;
    if (abs(texelFetch(u_normal_depth_prev, q, 0).w - expected) > u_depth_tolerance) return ao;
    return mix(texelFetch(u_ao_prev, q, 0).r, ao, u_alpha);
}

void main() {
    ivec2 p;
    if (fullscreen_pixel(p)) write_ao(p, accumulated(p));
}
