#version 450 core
// mboit_moments' fragment stage: the fragment's absorbance -ln(1 - alpha) and its power moments
// of the warped depth (oit_blend.glsl's oit_log_depth), added into the pixel's sums.
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"
#include "oit_blend.glsl"
#include "mboit_common.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the pass's colour hook (color_hook)

layout(location = 0) out vec4 o_b0;
layout(location = 1) out vec4 o_moments;
#if MBOIT_ORDER > 2
layout(location = 2) out vec4 o_moments_high;  // z^5..z^8 (power6: z^5, z^6)
#endif

void main() {
    LineFrag f = line_fragment();
    vec4 c = oit_fragment_rgba(f, line_color_hook(vec4(f.color, 1.0), f.point));
    if (!oit_fragment_visible(c.a)) discard;  // invisible: no contribution (and no coverage)
    float a = mboit_absorbance_of(c.a);
    o_b0 = vec4(a);
#ifdef MBOIT_TRIG
    // e^(i k phi), k = 1..n: the trigonometric moments
    vec2 c1 = mboit_circle(oit_log_depth(f)), c2 = mboit_cmul(c1, c1);
    o_moments = a * vec4(c1, c2);
#if MBOIT_ORDER == 3
    o_moments_high = a * vec4(mboit_cmul(c2, c1), 0.0, 0.0);
#elif MBOIT_ORDER == 4
    o_moments_high = a * vec4(mboit_cmul(c2, c1), mboit_cmul(c2, c2));
#endif
#else
    float z = oit_log_depth(f), z2 = z * z, z4 = z2 * z2;
    o_moments = a * vec4(z, z2, z2 * z, z4);
#if MBOIT_ORDER == 3
    o_moments_high = a * vec4(z4 * z, z4 * z2, 0.0, 0.0);
#elif MBOIT_ORDER == 4
    o_moments_high = a * z4 * vec4(z, z2, z2 * z, z4);
#endif
#endif
}
