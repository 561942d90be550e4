#version 450 core
// mboit_accum's fragment stage: the transmittance in front of the fragment from its pixel's
// moments (mboit_math.glsl), then its premultiplied colour and its opacity, both times that,
// added into the pixel's sums.
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"
#include "oit_blend.glsl"
#include "mboit_common.glsl"
#include "mboit_math.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the pass's colour hook (color_hook)

uniform sampler2D u_b0;
uniform sampler2D u_moments;
#if MBOIT_ORDER > 2
uniform sampler2D u_moments_high;
#endif
uniform float u_overestimation;
uniform float u_bias;  // moment_bias, the paper's where the parameter is < 0

layout(location = 0) out vec4 o_accum;

void main() {
    LineFrag f = line_fragment();
    vec4 c = oit_fragment_rgba(f, line_color_hook(vec4(f.color, 1.0), f.point));
    if (!oit_fragment_visible(c.a)) discard;
    ivec2 p = ivec2(gl_FragCoord.xy);
    float b0 = texelFetch(u_b0, p, 0).r;
    vec4 lo = texelFetch(u_moments, p, 0);
#if MBOIT_ORDER > 2
    vec4 hi = texelFetch(u_moments_high, p, 0);
#else
    vec4 hi = vec4(0.0);  // not read with 4 moments
#endif
    float b[8] = float[8](lo.x, lo.y, lo.z, lo.w, hi.x, hi.y, hi.z, hi.w);
    float t = mboit_transmittance(b0, b, oit_log_depth(f), u_bias, u_overestimation);
    float a = mboit_alpha(c.a);
    o_accum = vec4(oit_core_ao(c.rgb, f) * a, a) * t;
}
