#version 450 core
#include "line_hooks.glsl"
uniform int u_mode;
float line_width_hook(LinePoint p) { return u_mode == 2 ? 1.0 - p.age : 1.0; }
