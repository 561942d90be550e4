#version 450 core
// fade_core's colour hook: keeps a fragment where the pathlet's end fade is at least
// u_core_alpha (the opaque core LineAO can trust) and drops the faded ends.
#include "line_fade.glsl"

uniform float u_core_alpha;

vec4 line_color_hook(vec4 rgba, LinePoint p) { return vec4(rgba.rgb, line_end_fade(p) >= u_core_alpha ? 1.0 : 0.0); }
