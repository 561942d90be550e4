#version 450 core
// volume_ao per pixel: the kit's estimate from the density volume (line_volume_ao.glsl) for
// the G-buffer's point and normal and the line's axis from the tangent target; optionally
// times a weighted screen-space term (the hybrid).
#include "fullscreen_pass.glsl"
#include "line_volume_ao.glsl"

uniform sampler2D u_normal_depth;  // the pins and the parameter, by declaration
uniform sampler2D u_tangent;
#ifdef SCREEN_AO
uniform sampler2D u_screen_ao;
uniform float u_screen_weight;
#endif

#ifdef FULLSCREEN_COMPUTE
layout(r16f) writeonly uniform image2D u_ao;
void write_ao(ivec2 p, float ao) { imageStore(u_ao, p, vec4(ao)); }
#else
layout(location = 0) out float o_ao;
void write_ao(ivec2 p, float ao) { o_ao = ao; }
#endif

float pixel_ao(ivec2 px) {
    vec4 nd = texelFetch(u_normal_depth, px, 0);
    if (dot(nd.xyz, nd.xyz) < 0.01) return 1.0;  // background
    vec4 tw = texelFetch(u_tangent, px, 0);
    float ao = line_volume_ao_gbuffer(vec2(px) + 0.5, nd.w, nd.xyz, tw.xyz, tw.w);
#ifdef SCREEN_AO
    ao *= mix(1.0, texelFetch(u_screen_ao, px, 0).r, u_screen_weight);
#endif
    return ao;
}

void main() {
    ivec2 px;
    if (fullscreen_pixel(px)) write_ao(px, pixel_ao(px));
}
