#version 450 core
// geometric_fade's width hook: pathlet ends taper in width instead of opacity (variant 3 of
// the study). The line kit calls it at every quad corner and derives the tube normal and depth
// from the tapered width, so the tube stays round down to the tip.
#include "line_hooks.glsl"

uniform vec2 u_fade;        // tail, head taper lengths: in age (time mode) or world units (arc length)
uniform int u_measure;      // 0: time (the pathlet's age), 1: arc length
uniform int u_curve;        // 0 linear, 1 smooth (Hermite), 2 round (sqrt: a fuller, cap-like tip)
uniform float u_min_width;  // width left at the very end, as a fraction of the full width

// x: 0 at the end, 1 where the full width starts.
float taper(float x) {
    x = clamp(x, 0.0, 1.0);
    float w = u_curve == 1 ? x * x * (3.0 - 2.0 * x) : (u_curve == 2 ? sqrt(x) : x);
    return mix(u_min_width, 1.0, w);
}

float line_width_hook(LinePoint p) {
    float from_tail = u_measure == 0 ? 1.0 - p.age : p.arc_from_tail;
    float from_head = u_measure == 0 ? p.age : p.arc_from_head;
    float tail = u_fade.x > 0.0 ? taper(from_tail / u_fade.x) : 1.0;
    float head = u_fade.y > 0.0 ? taper(from_head / u_fade.y) : 1.0;
    return min(tail, head);
}
