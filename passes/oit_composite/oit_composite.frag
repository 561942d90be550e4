#version 450 core
// oit_composite: the weighted mean colour of the pixel's fragments, accum.rgb / accum.a, covers
// 1 - T of the pixel and the background the transmittance T (WBOIT: the revealage; MBOIT: exp of
// minus the total absorbance b0).
uniform sampler2D u_accum;
#ifdef TRANSMITTANCE_FROM_REVEALAGE
uniform sampler2D u_revealage;
#else
uniform sampler2D u_absorbance;
#endif
uniform vec3 u_background;

layout(location = 0) out vec4 o_color;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 acc = texelFetch(u_accum, p, 0);
#ifdef TRANSMITTANCE_FROM_REVEALAGE
    float t = clamp(texelFetch(u_revealage, p, 0).r, 0.0, 1.0);
#else
    float t = exp(-max(texelFetch(u_absorbance, p, 0).r, 0.0));
#endif
    if (!(acc.a > 0.0)) {  // no fragment (or none with weight)
        o_color = vec4(u_background, 0.0);
        return;
    }
    o_color = vec4(clamp(acc.rgb / acc.a, 0.0, 1.0) * (1.0 - t) + u_background * t, 1.0);
}
