#version 450 core
// geometric_fade's width hook: pathlet ends taper in width instead of opacity (variant 3 of
// the study). The line kit calls it at every quad corner and derives the tube normal and depth
// from the tapered width, so the tube stays round down to the tip.
#include "line_fade.glsl"

float line_width_hook(LinePoint p) { return line_end_fade(p); }
