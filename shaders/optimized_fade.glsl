#version 450 core
// Variant 4's colour hook (fill_list): the end fade of variant 2 (line_fade.glsl) times the
// opacity opacity optimization gave the point's segment (oo_opacity.glsl; connect the pass's
// hook_buffer to opacity_blend's `opacity`).
#include "line_fade.glsl"
#include "oo_opacity.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p) { return vec4(rgba.rgb, rgba.a * line_end_fade(p) * optimized_opacity(p)); }
