#version 450 core
// The line kit's default width hook: every pathlet at its full width.
#include "line_hooks.glsl"
float line_width_hook(LinePoint p) { return 1.0; }
