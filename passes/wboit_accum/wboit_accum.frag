#version 450 core
// wboit_accum's fragment stage: the fragment's colour and opacity as fill_list would store them
// (oit_blend.glsl), weighted by depth and opacity (McGuire & Bavoil 2013), into the sums that
// oit_composite divides: accum += (c a w, a w) (blend ONE, ONE), revealage *= 1 - a (blend
// ZERO, ONE_MINUS_SRC_COLOR).
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"
#include "oit_blend.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the pass's colour hook (color_hook)

uniform int u_weight;  // the choice's index: 0 exponential, 1 depth_cubed, 2 linevis
uniform float u_falloff;  // exponential: the weight's e-folds over [near, far]

layout(location = 0) out vec4 o_accum;
layout(location = 1) out vec4 o_revealage;

// The published weights (float32 sums hold them: no range to save), and a steeper one.
float wboit_weight(float a, float d) {
    if (u_weight == 0) return a * max(1e-4, 3e3 * exp(-u_falloff * d));
    if (u_weight == 2) {
        float s = min(1.0, a) * 8.0 + 0.01, t = 1.0 - 0.95 * d;
        return clamp(s * s * s * 1e8 * t * t * t, 1e-2, 3e2);
    }
    float t = 1.0 - d;
    return a * max(1e-2, 3e3 * t * t * t);
}

void main() {
    LineFrag f = line_fragment();
    vec4 c = oit_fragment_rgba(f, line_color_hook(vec4(f.color, 1.0), f.point));
    if (!oit_fragment_visible(c.a)) discard;  // invisible: no contribution (and no coverage)
    c.rgb = oit_core_ao(c.rgb, f);
    float w = wboit_weight(c.a, f.depth01);
    o_accum = vec4(c.rgb * c.a, c.a) * w;
    o_revealage = vec4(c.a);
}
