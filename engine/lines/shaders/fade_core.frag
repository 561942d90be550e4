#version 450 core
// The opaque core of opacity-faded pathlets (fade_core's default colour hook): keeps a fragment
// where the pathlet's end fade is at least core_alpha (the geometry LineAO can trust) and
// drops the faded ends. The end fade's parameters come from line_fade.glsl.
#include "line_fade.glsl"

uniform float u_core_alpha;  // @param 0.5 [0, 1] "opacity from which a fragment belongs to the core"

vec4 line_color_hook(vec4 rgba, LinePoint p) { return vec4(rgba.rgb, line_end_fade(p) >= u_core_alpha ? 1.0 : 0.0); }
