#version 450 core
#include "line_hooks.glsl"
uniform int u_mode;
uniform float u_scale;
float line_width_hook(LinePoint p) { return u_mode == 2 ? 1.0 - p.age : u_mode == 4 ? u_scale : 1.0; }
