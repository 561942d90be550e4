#version 450 core
// A baseline for opacity optimization: the end fade of variant 2 times one opacity for every
// line (tune it to the optimized picture's coverage to compare like with like).
#include "line_fade.glsl"

uniform float u_opacity;  // @param 0.5 [0, 1] "opacity of every line (times the end fade)"

vec4 line_color_hook(vec4 rgba, LinePoint p) { return vec4(rgba.rgb, rgba.a * line_end_fade(p) * u_opacity); }
