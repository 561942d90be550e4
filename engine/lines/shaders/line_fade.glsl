// The line kit's end fade: a factor that rises from the pathlet's tail and falls to its head,
// shared by every fade strategy (fade_opacity.frag fades the opacity with it, fade_width.geom
// tapers the width; fade_core keeps where a colour hook reaches core_alpha). Include it from a hook file: its
// parameters (below, @param) become parameters of every pass whose hook includes it.
#ifndef PATHLET_LINE_FADE_GLSL
#define PATHLET_LINE_FADE_GLSL

#include "line_hooks.glsl"

uniform float u_tail_fade;  // @param 0.5 [0, 1] "length of the fade at the tail (the oldest end), as a share of the pathlet: of the window (fade_measure=time) or of a typical pathlet's length (arc_length); 0 = none"
uniform float u_head_fade;  // @param 0.15 [0, 1] "length of the fade at the head (the newest end), the same way; 0 = none"
uniform int u_fade_measure;  // @param time {time, arc_length} "time: fade over a share of the window, as in the study (fast pathlets get long fades, slow ones short); arc_length: over a fixed length along the line (share x median speed x window), the same on screen for every pathlet"
uniform int u_fade_curve;  // @param linear {linear, smooth, round} "profile along the fade: linear, smooth (Hermite), round (sqrt: fuller ends)"
uniform float u_fade_floor;  // @param 0 [0, 1] "value left at the very end (0 = nothing)"

// x: 0 at the end, 1 where the fade is over.
float line_fade_curve(float x) {
    x = clamp(x, 0.0, 1.0);
    float w = u_fade_curve == 1 ? x * x * (3.0 - 2.0 * x) : (u_fade_curve == 2 ? sqrt(x) : x);
    return mix(u_fade_floor, 1.0, w);
}

// 1 in the body of the pathlet, falling to u_fade_floor at its tail and at its head. The
// lengths are shares of the window (time: the age is one already) or of a typical pathlet's
// length (arc length: u_typical_length, from the kit).
float line_end_fade(LinePoint p) {
    vec2 fade = vec2(u_tail_fade, u_head_fade) * (u_fade_measure == 0 ? 1.0 : u_typical_length);
    float from_tail = u_fade_measure == 0 ? 1.0 - p.age : p.arc_from_tail;
    float from_head = u_fade_measure == 0 ? p.age : p.arc_from_head;
    float tail = fade.x > 0.0 ? line_fade_curve(from_tail / fade.x) : 1.0;
    float head = fade.y > 0.0 ? line_fade_curve(from_head / fade.y) : 1.0;
    return min(tail, head);
}

#endif
