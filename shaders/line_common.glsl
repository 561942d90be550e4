// Shared by every stage that draws pathlet quads (line_quad.geom and the gbuffer / isl
// passes). A stage file defines one of LINE_STAGE_VERTEX, LINE_STAGE_GEOMETRY or
// LINE_STAGE_FRAGMENT before including this, and gets that stage's interface and helpers.
// The uniforms are set by passes/gbuffer/line_pass.hpp.
#ifndef PATHLET_LINE_COMMON_GLSL
#define PATHLET_LINE_COMMON_GLSL

uniform mat4 u_view;
uniform mat4 u_proj;
uniform vec2 u_window;       // [t0, t1] in seconds
uniform int u_windowed;      // 0: draw lines whole
uniform float u_half_width;  // world units, half the quad width (halo included)
uniform float u_halo;        // fraction of the width that is halo (0 = none)
uniform float u_halo_depth;  // push-back at the rim, normalised linear depth
uniform vec3 u_halo_color;
uniform vec2 u_depth_range;  // camera near, far
uniform vec2 u_speed_range;  // speed mapped to colour 0 and 1
uniform int u_colormap;

vec3 line_safe_normalize(vec3 v, vec3 fallback) {
    float l = length(v);
    return l > 1e-12 ? v / l : fallback;
}

// Members of the stage interfaces (a block name must match across stages; members too).
// position and tangent are in view space.
#define LINE_VERTEX_MEMBERS vec3 position; float time; float speed; vec3 tangent; flat int line_id;
// pos_view: point on the flat quad; side: unit vector across it (s = +1 side);
// s: -1..1 across the width.
#define LINE_FRAGMENT_MEMBERS vec3 pos_view; vec3 side; vec3 tangent; float s; float speed; flat int line_id;

#ifdef LINE_STAGE_VERTEX
layout(location = 0) in vec3 a_position;
layout(location = 1) in float a_time;
layout(location = 2) in vec3 a_velocity;
layout(location = 3) in vec3 a_tangent;
layout(location = 4) in int a_line_id;
out LineVertex { LINE_VERTEX_MEMBERS } v_out;

// View-space point and tangent, once per point (a point is shared by two segments, and
// llvmpipe runs the GS single-threaded, so per-point work belongs here).
void line_vertex() {
    v_out.position = (u_view * vec4(a_position, 1.0)).xyz;
    v_out.time = a_time;
    v_out.speed = length(a_velocity);
    v_out.tangent = mat3(u_view) * a_tangent;
    v_out.line_id = a_line_id;
}
#endif

#ifdef LINE_STAGE_GEOMETRY
in LineVertex { LINE_VERTEX_MEMBERS } v_in[];
out LineFragment { LINE_FRAGMENT_MEMBERS } g_out;
#endif

#ifdef LINE_STAGE_FRAGMENT
#include "colormap.glsl"

in LineFragment { LINE_FRAGMENT_MEMBERS } g_in;

struct LineFrag {
    vec3 color;       // colour-mapped speed, before halos and lighting
    vec3 normal;      // view-space unit normal of the fake tube
    vec3 tangent;     // view-space unit tangent
    vec3 to_viewer;   // view-space unit vector from the fragment to the eye
    float eye_depth;  // distance along -z to the tube surface (world units)
    float depth01;    // linear depth over [near, far], halo push-back included, in [0,1]
    float halo;       // 0 outside the halo band, then 0..1 from its inner edge to the rim
    bool in_halo;
};

LineFrag line_fragment() {
    LineFrag f;
    float s = clamp(g_in.s, -1.0, 1.0);
    float c = sqrt(max(1.0 - s * s, 0.0));
    vec3 side = line_safe_normalize(g_in.side, vec3(1.0, 0.0, 0.0));
    f.to_viewer = line_safe_normalize(-g_in.pos_view, vec3(0.0, 0.0, 1.0));
    // Circle cross-section: -side, through the view direction, to +side (not a linear blend).
    vec3 v = line_safe_normalize(f.to_viewer - dot(f.to_viewer, side) * side, vec3(0.0, 0.0, 1.0));
    f.normal = line_safe_normalize(s * side + c * v, v);
    f.tangent = line_safe_normalize(g_in.tangent, vec3(0.0, 1.0, 0.0));
    // Convex tube: the surface bulges towards the viewer by r * sqrt(1 - s^2).
    float near = u_depth_range.x, far = u_depth_range.y;
    f.eye_depth = max(-g_in.pos_view.z - u_half_width * c, 1e-6);
    float inner = 1.0 - u_halo;
    f.in_halo = u_halo > 0.0 && abs(s) > inner;
    f.halo = f.in_halo ? clamp((abs(s) - inner) / u_halo, 0.0, 1.0) : 0.0;
    // Halos go back in proportion to their distance into the band: close lines merge, far ones gap.
    f.depth01 = clamp((f.eye_depth - near) / max(far - near, 1e-6) + u_halo_depth * f.halo, 0.0, 1.0);
    float span = max(u_speed_range.y - u_speed_range.x, 1e-12);
    f.color = colormap(u_colormap, (g_in.speed - u_speed_range.x) / span);
    return f;
}

// The halo is a gradient from half-way to the full halo colour at the rim, so its start
// still marks the line's edge (the study: halos read by the start and end of the gradient).
vec3 line_halo_tint(vec3 color, LineFrag f) {
    return f.in_halo ? mix(color, u_halo_color, 0.5 + 0.5 * f.halo) : color;
}

// Window-space depth of linear depth d01, so the z-buffer sees tubes and pushed-back halos.
float line_window_depth(float d01) {
    float z = mix(u_depth_range.x, u_depth_range.y, d01);  // distance along -z
    float ndc = (u_proj[2][2] * -z + u_proj[3][2]) / z;
    return clamp(0.5 * ndc + 0.5, 0.0, 1.0);
}
#endif

#endif
