#version 450 core
// The line kit's geometry stage: one line-strip segment -> one view-aligned quad (4-vertex
// strip). The quad is clipped to the time window by interpolating in time, so pathlet heads
// and tails move smoothly instead of jumping a whole segment per data step. Each end uses the
// per-point tangent, so the quads of neighbouring segments meet at the same edge (smooth
// joints, no gaps), and its width comes from the pass's width hook (line_hooks.glsl) at that
// end, so a taper is exact where the window clips a segment.
#define LINE_STAGE_GEOMETRY
#include "line_common.glsl"

layout(lines) in;
#ifdef LINE_WIDTH_HOOKED
// A width hook is evaluated at the quad ends and interpolated between them. The level of detail
// (pathlet/line_lod.hpp) may join many data segments into one, which would coarsen a taper, so a
// hooked width splits the segment back into as many pieces as data segments it stands for (up
// to 16): a width hook sees the data's resolution.
const int kMaxPieces = 16;
uniform int u_lod_max_skip;  // set by lines::Drawer (kWidthHookMaxSkip), at most kMaxPieces
layout(triangle_strip, max_vertices = 34) out;
#else
layout(triangle_strip, max_vertices = 4) out;
#endif

float line_width_hook(LinePoint p);  // the pass's hook, linked in beside this file

bool finite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

void emit_end(vec3 p, vec3 t_view, LinePoint lp) {
    vec3 t = line_safe_normalize(t_view, vec3(0.0, 1.0, 0.0));
    vec3 to_viewer = line_safe_normalize(-p, vec3(0.0, 0.0, 1.0));
    // Across the line and facing the viewer; a line seen end-on gets any perpendicular.
    vec3 side = cross(t, to_viewer);
    if (dot(side, side) < 1e-12) side = cross(vec3(0.0, 1.0, 0.0), to_viewer);
    if (dot(side, side) < 1e-12) side = cross(vec3(1.0, 0.0, 0.0), to_viewer);
    side = normalize(side);
    // Clamped: post passes skip what lies beyond the widest quad allowed for (lines::screen_rect).
    float hw = u_half_width * clamp(line_width_hook(lp), 0.0, u_max_width_hook);
    for (int k = 0; k < 2; ++k) {
        float s = k == 0 ? -1.0 : 1.0;
        g_out.pos_view = p + s * hw * side;
        g_out.side = side;
        g_out.tangent = t;
        g_out.s = s;
        g_out.speed = lp.speed;
        g_out.time = lp.time;
        g_out.age = lp.age;
        g_out.arc_head = lp.arc_from_head;
        g_out.arc_tail = lp.arc_from_tail;
        g_out.arc = lp.arc;
        g_out.half_width = hw;
        g_out.line_id = lp.line_id;
        gl_Position = u_proj * vec4(g_out.pos_view, 1.0);
        EmitVertex();
    }
}

void main() {
    vec3 p0 = v_in[0].position, p1 = v_in[1].position;
    if (!finite3(p0) || !finite3(p1)) return;  // bad data points: skip, never NaN quads
    float t0 = v_in[0].time, t1 = v_in[1].time;
    float fa = 0.0, fb = 1.0;
    if (u_windowed != 0) {
        if (t1 < u_window.x || t0 > u_window.y) return;
        float dt = t1 - t0;
        if (dt > 1e-9) {
            fa = clamp((u_window.x - t0) / dt, 0.0, 1.0);
            fb = clamp((u_window.y - t0) / dt, 0.0, 1.0);
        }
    }
    int id = v_in[0].line_id;
    int pieces = 1;
#ifdef LINE_WIDTH_HOOKED
    pieces = clamp(int(ceil((fb - fa) * float(v_in[1].point - v_in[0].point))), 1, min(u_lod_max_skip, kMaxPieces));
#endif
    for (int k = 0; k <= pieces; ++k) {
        float f = mix(fa, fb, float(k) / float(pieces));
        vec3 t = line_safe_normalize(mix(v_in[0].tangent, v_in[1].tangent, f), v_in[k == 0 ? 0 : 1].tangent);
        vec3 p = mix(p0, p1, f);
        emit_end(p, t, line_point(p, mix(t0, t1, f), mix(v_in[0].arc, v_in[1].arc, f), mix(v_in[0].speed, v_in[1].speed, f), id));
    }
    EndPrimitive();
}
