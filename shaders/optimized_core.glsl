#version 450 core
// Variant 4's opaque core (fade_core's colour hook): a fragment belongs to the core that LineAO
// lights where the end fade times the optimized opacity reaches core_alpha, so AO is computed
// on what the optimization left visible (connect the pass's hook_buffer to opacity_blend's
// `opacity`).
#include "line_fade.glsl"
#include "oo_opacity.glsl"

uniform float u_core_alpha;  // @param 0.5 [0, 1] "opacity from which a fragment belongs to the core"

vec4 line_color_hook(vec4 rgba, LinePoint p) {
    return vec4(rgba.rgb, line_end_fade(p) * optimized_opacity(p) >= u_core_alpha ? 1.0 : 0.0);
}
