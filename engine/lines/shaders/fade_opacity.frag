#version 450 core
// The kit's opacity fade (variant 2 of the study, fill_list's default colour hook): pathlet
// ends fade out in opacity, over the end fade of line_fade.glsl (tail_fade, head_fade,
// fade_measure, ...). In an OIT pipeline (fill_list) that is real transparency; on an opaque
// G-buffer the kit turns it into screen-door coverage.
#include "line_fade.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p) { return vec4(rgba.rgb, rgba.a * line_end_fade(p)); }
