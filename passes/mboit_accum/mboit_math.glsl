// The transmittance in front of depth z0 from a pixel's 4 power moments (Münstermann et al.
// 2018, after Peters & Klein's moment shadow maps), derived here:
//  1. the normalised moments m_k = b_k / b0 (m_0 = 1) are biased towards those of the uniform
//     distribution on [-1, 1] (0, 1/3, 0, 1/5), so the Hankel matrix H_ij = m_(i+j),
//     i, j = 0..2, is positive definite;
//  2. H c = (1, z0, z0^2), solved as H = L D L^T with a unit lower L; the two roots of
//     c0 + c1 x + c2 x^2 with z0 are the support of the distribution with these moments that
//     has a point at z0 (its canonical representation);
//  3. the quadratic p that is beta (the overestimation) at z0, 1 at a support point in front
//     of z0 and 0 behind interpolates the share of absorbance in front of z0; its expectation,
//     from the Newton form of p, needs only m_1 and m_2.
// The transmittance is exp(-b0 x that share).
#ifndef PATHLET_MBOIT_MATH_GLSL
#define PATHLET_MBOIT_MATH_GLSL

// The two roots of a2 x^2 + a1 x + a0 (real by construction; a negative discriminant from
// rounding counts as 0), without cancellation.
void mboit_quadratic_roots(float a2, float a1, float a0, out float r0, out float r1) {
    float disc = sqrt(max(a1 * a1 - 4.0 * a2 * a0, 0.0));
    float t = -0.5 * (a1 + (a1 >= 0.0 ? disc : -disc));
    r0 = t / a2;
    r1 = t != 0.0 ? a0 / t : r0;
}

// Transmittance at warped depth z0 of a pixel with total absorbance b0 and moments b = sum of
// absorbance x (z, z^2, z^3, z^4).
float mboit_transmittance(float b0, vec4 b, float z0, float bias, float beta) {
    if (b0 <= 1e-6) return 1.0;
    vec4 m = mix(b / b0, vec4(0.0, 1.0 / 3.0, 0.0, 1.0 / 5.0), bias);
    float d1 = m.y - m.x * m.x;
    float l21 = (m.z - m.x * m.y) / d1;
    float d2 = (m.w - m.y * m.y) - l21 * l21 * d1;
    float y1 = (z0 - m.x) / d1;
    float c2 = (z0 * z0 - m.y - l21 * (z0 - m.x)) / d2;
    float c1 = y1 - l21 * c2;
    float c0 = 1.0 - m.x * c1 - m.y * c2;
    float z1, z2;
    mboit_quadratic_roots(c2, c1, c0, z1, z2);
    float f1 = z1 < z0 ? 1.0 : 0.0, f2 = z2 < z0 ? 1.0 : 0.0;
    float f01 = (f1 - beta) / (z1 - z0), f12 = (f2 - f1) / (z2 - z1);
    float f012 = (f12 - f01) / (z2 - z0);
    float share = beta + f01 * (m.x - z0) + f012 * (m.y - (z0 + z1) * m.x + z0 * z1);
    return clamp(exp(-b0 * share), 0.0, 1.0);
}
#endif
