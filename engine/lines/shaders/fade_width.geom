#version 450 core
// The kit's taper (variant 3 of the study, geometric_fade's default width hook): pathlet ends
// taper in width instead of opacity. The kit calls it at every quad corner and derives the tube
// normal and depth from the tapered width, so the tube stays round down to the tip. Its
// parameters are the end fade's (line_fade.glsl: tail_fade, head_fade, fade_measure, ...).
#include "line_fade.glsl"

float line_width_hook(LinePoint p) { return line_end_fade(p); }
