#version 450 core
// The line kit's default colour hook: the colour-mapped speed as it is, opaque.
#include "line_hooks.glsl"
vec4 line_color_hook(vec4 rgba, LinePoint p) { return rgba; }
