// The line kit's end fade: a factor that rises from the pathlet's tail and falls to its head,
// shared by every fade strategy (geometric_fade tapers the width with it, fill_list the
// opacity). Include it from a hook file; the uniforms are set by lines::EndFade (C++).
#ifndef PATHLET_LINE_FADE_GLSL
#define PATHLET_LINE_FADE_GLSL

#include "line_hooks.glsl"

uniform vec2 u_fade;          // tail, head fade lengths: in age (time) or world units (arc length)
uniform int u_fade_measure;   // 0: time (the pathlet's age), 1: arc length
uniform int u_fade_curve;     // 0 linear, 1 smooth (Hermite), 2 round (sqrt: fuller ends)
uniform float u_fade_floor;   // value left at the very end

// x: 0 at the end, 1 where the fade is over.
float line_fade_curve(float x) {
    x = clamp(x, 0.0, 1.0);
    float w = u_fade_curve == 1 ? x * x * (3.0 - 2.0 * x) : (u_fade_curve == 2 ? sqrt(x) : x);
    return mix(u_fade_floor, 1.0, w);
}

// 1 in the body of the pathlet, falling to u_fade_floor at its tail and at its head.
float line_end_fade(LinePoint p) {
    float from_tail = u_fade_measure == 0 ? 1.0 - p.age : p.arc_from_tail;
    float from_head = u_fade_measure == 0 ? p.age : p.arc_from_head;
    float tail = u_fade.x > 0.0 ? line_fade_curve(from_tail / u_fade.x) : 1.0;
    float head = u_fade.y > 0.0 ? line_fade_curve(from_head / u_fade.y) : 1.0;
    return min(tail, head);
}

#endif
