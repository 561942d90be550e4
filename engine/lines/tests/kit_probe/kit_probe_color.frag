#version 450 core
#include "line_hooks.glsl"
uniform int u_mode;
uniform float u_scale;
vec4 line_color_hook(vec4 rgba, LinePoint p) {
    if (u_mode == 0) return vec4(p.age, 0.0, 0.0, 1.0);
    if (u_mode == 1) return vec4(p.arc_from_head / u_scale, p.arc_from_tail / u_scale, 0.0, 1.0);
    return rgba;
}
