#version 450 core
// A baseline for opacity optimization: a speed -> opacity transfer function times the end fade
// of variant 2. The speed is measured on the colour map's range (the data's 1st to 99th
// percentile unless speed_min/speed_max say otherwise), a fixed range, so nothing flickers.
#include "line_fade.glsl"

uniform float u_opacity_slow;  // @param 0.1 [0, 1] "opacity at the colour map's lowest speed"
uniform float u_opacity_fast;  // @param 1 [0, 1] "opacity at its highest speed (linear between)"

vec4 line_color_hook(vec4 rgba, LinePoint p) {
    float s = clamp((p.speed - u_speed_range.x) / max(u_speed_range.y - u_speed_range.x, 1e-12), 0.0, 1.0);
    return vec4(rgba.rgb, rgba.a * line_end_fade(p) * mix(u_opacity_slow, u_opacity_fast, s));
}
