#version 450 core
// The line kit's G-buffer stage (LineAO's inputs) per fragment of a pathlet quad: colour (speed
// map through the pass's colour hook, then halo), view-space tube normal + normalised linear
// depth, zoom (pixels per world unit), optionally the line id. The hook's alpha becomes
// screen-door coverage: the targets are opaque, so a fading fragment survives on a share of
// the pixels (alpha 1 keeps them all). Optionally the rim in pixels for edge_aa's coverage.
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the pass's hook, linked in beside this file

uniform float u_zoom_scale;  // (H/2) * P[1][1]

layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_normal_depth;
layout(location = 2) out float o_zoom;
#ifdef WRITE_LINE_ID
layout(location = LINE_ID_LOCATION) out int o_line_id;
#endif
#ifdef WRITE_EDGE  // the rim for edge_aa (line_edge in line_common.glsl)
layout(location = EDGE_LOCATION) out vec4 o_edge;
#endif
#ifdef WRITE_TANGENT  // the tube's axis for volume_ao: tangent, eye depth to the axis' quad
layout(location = TANGENT_LOCATION) out vec4 o_tangent;
#endif

void main() {
    LineFrag f = line_fragment();
    vec4 c = line_color_hook(vec4(f.color, 1.0), f.point);
#ifndef LINE_OPAQUE  // the default colour hook is opaque: no screen door, no discard
    if (c.a < line_screen_door_threshold(gl_FragCoord.xy)) discard;
#endif
    o_color = vec4(line_halo_tint(c.rgb, f), 1.0);
    o_normal_depth = vec4(f.normal, f.depth01);
    o_zoom = u_zoom_scale / f.eye_depth;
#ifdef WRITE_LINE_ID
    o_line_id = g_in.line_id;
#endif
#ifdef WRITE_EDGE
    o_edge = line_edge(f);
#endif
#ifdef WRITE_TANGENT
    o_tangent = vec4(f.tangent, -g_in.pos_view.z - mix(u_depth_range.x, u_depth_range.y, f.depth01));
#endif
    gl_FragDepth = line_window_depth(f.depth01);
}
