// The transmittance in front of warped depth z0 from a pixel's 4, 6 or 8 power moments
// (MBOIT_ORDER n = 2, 3, 4: 2n moments; Münstermann et al. 2018, after Peters & Klein's moment
// shadow maps), derived here:
//  1. the normalised moments m_k = b_k / b0 (m_0 = 1) are biased towards those of the uniform
//     distribution on [-1, 1] (0, 1/3, 0, 1/5, ..), so the Hankel matrix H_ij = m_(i+j),
//     i, j = 0..n, is positive definite; H = L D L^T. In exact arithmetic the bias gives
//     D_jj >= bias x D_jj of the uniform distribution (D_jj = min E[p^2] over monic p of
//     degree j, and E is a mix of the data's and the uniform's). That floor is reached only
//     where the data's points add nothing to the minimum, which is rare: one fragment at z has
//     D_11 = bias (1/3 + (1 - bias) z^2), above the floor unless z = 0, because the mixture
//     adds the term between the two means. So a pixel with fewer layers than n has D_jj of
//     the floor's order (about bias), not at it, and float32 sums leave rounding noise there:
//     the roots of step 2 can be garbage (lone lines dropped out in dashes with 4 moments on
//     the CFD aorta; an earlier 6/8-moment attempt drew white single-fragment pixels). The
//     order is cut at the first D_jj at or below the floor, where it is noise for certain.
//     That cut does not catch most such pixels; what makes them come out right is step 3 at
//     the fragment's own depth: there every orthogonal polynomial y_j (j >= 1) of the
//     pixel's distribution nearly vanishes (one fragment at z_a: y_1(z_a) = bias z_a), so
//     K(z0, z0) = sum y_j(z0)^2 / D_jj is near 1 and the weight at z0 holds nearly all the
//     mass, whatever the noisy D_jj do to the other support points. With 6 and 8 moments at
//     the default bias the floors of D_33 and D_44 (5e-7 x 4/175 = 1.1e-8, 5e-7 x 64/11025 =
//     2.9e-9) lie below float32 rounding of the moments (|m| x eps, about 1e-7): for pixels
//     of 2 or 3 layers the cut fires only where that noise comes out negative.
//  2. H_k c = (1, z0, .., z0^k) on the leading block; the k real roots of sum c_i x^i with z0
//     are the support of the distribution with these moments that has a point at z0 (its
//     canonical representation): closed forms below, roots of cubics and quartics polished
//     by Newton steps.
//  3. the share of the absorbance in front of z0: the support points' weights (Christoffel
//     numbers 1 / K(z_i, z_i)) times 1 in front of z0, 0 behind and beta (the overestimation)
//     at z0. The paper takes the expectation of the polynomial through these values from its
//     monomial coefficients, which cancels (divided differences of layers 1e-3 apart are
//     1e6); the weights are sums of positive terms.
// The transmittance is exp(-b0 x that share). The paper's code (and LineVis' GLSL port,
// MomentMath.glsl) unrolls each order by hand; here one loop serves all three.
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

#ifndef MBOIT_ORDER
#define MBOIT_ORDER 2
#endif
const int kMboitN = MBOIT_ORDER;
const float kMboitUniformD[5] = float[5](1.0, 1.0 / 3.0, 4.0 / 45.0, 4.0 / 175.0, 64.0 / 11025.0);
// D_jj at or below the bias' floor is rounding noise for certain (a larger factor cut real
// layers of the phantoms' tight bundles and made the picture worse).
const float kMboitKeep = 1.0;

// c[0] + c[1] x + .. + c[4] x^4 and its derivative (coefficients above the order are 0).
float mboit_horner(float c[5], float x) {
    float v = c[4];
    for (int i = 3; i >= 0; --i) v = v * x + c[i];
    return v;
}
float mboit_horner_d(float c[5], float x) {
    float v = 4.0 * c[4];
    for (int i = 3; i >= 1; --i) v = v * x + float(i) * c[i];
    return v;
}

// Real roots of x^3 + a x^2 + b x + c (three by construction), Viete's trigonometric form.
void mboit_cubic_roots(float a, float b, float c, out float r[3]) {
    float p = b - a * a / 3.0, q = (2.0 * a * a - 9.0 * b) * a / 27.0 + c;
    float s = sqrt(max(-p / 3.0, 0.0));
    float arg = s > 0.0 ? clamp(-q / (2.0 * s * s * s), -1.0, 1.0) : 0.0;
    float th = acos(arg) / 3.0;
    const float third = 2.0943951;  // 2 pi / 3
    for (int i = 0; i < 3; ++i) r[i] = 2.0 * s * cos(th - third * float(i)) - a / 3.0;
}

// Real roots of x^4 + a x^3 + b x^2 + c x + d (four by construction): Ferrari's factorisation
// into two quadratics with the resolvent cubic's largest root (the well-conditioned one).
void mboit_quartic_roots(float a, float b, float c, float d, out float r[4]) {
    float a2 = a * a;
    float p = b - 0.375 * a2, q = c - 0.5 * a * b + 0.125 * a2 * a;
    float s = d - 0.25 * a * c + (b - 0.1875 * a2) * a2 / 16.0;
    // (y^2 + p/2 + u)^2 = 2u y^2 - q y + u^2 + u p + p^2/4 - s, a square for
    // 8u^3 + 8p u^2 + (2p^2 - 8s) u - q^2 = 0.
    float ru[3];
    mboit_cubic_roots(p, 0.25 * p * p - s, -0.125 * q * q, ru);
    float u = max(max(ru[0], ru[1]), max(ru[2], 1e-12));
    float w = sqrt(2.0 * u), h = 0.5 * p + u, g = q / (2.0 * w);
    mboit_quadratic_roots(1.0, -w, h + g, r[0], r[1]);
    mboit_quadratic_roots(1.0, w, h - g, r[2], r[3]);
    for (int i = 0; i < 4; ++i) r[i] -= 0.25 * a;
}

// The transmittance at warped depth z0 from b0 and b = sum of absorbance x z^k, k = 1..2n.
#ifdef MBOIT_TRIG
// Trigonometric moments (moment_form trig2..trig4, MBOIT_ORDER n = 2..4 complex moments
// t_k = E[e^(i k phi)], mboit_common.glsl's mboit_circle), the same three steps on the circle:
// the moments are biased towards the uniform distribution's (t_k = 0), the Toeplitz matrix
// T_jk = t_(j-k) is factored as L D L^H (its pivots are at least bias: the order is cut below),
// T c = (1, x0, .., x0^k) for x0 = e^(i phi0), the roots of sum conj(c_j) x^j (on the unit circle)
// by Durand-Kerner iterations from points spread on the circle, and the share in front of x0
// from their Christoffel weights 1 / sum |y_j|^2 / D_jj, L y = (1, x, ..). A root's weight
// counts 1 when its angle is below phi0, and rises from 0 to 1 across the wrapping zone
// (between the farthest depth and, wrapping round, the nearest). The paper's code (LineVis:
// TrigonometricMomentMath.glsl) uses closed-form complex root solvers and the interpolating
// polynomial; the result is the same in exact arithmetic.
vec2 mboit_cdiv(vec2 a, vec2 b) { return vec2(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) / dot(b, b); }
vec2 mboit_conj(vec2 a) { return vec2(a.x, -a.y); }

float mboit_transmittance(float b0, float b[8], float z0, float bias, float beta) {
    if (b0 <= 1e-6) return 1.0;
    const int N = kMboitN;
    vec2 t[N + 1];
    t[0] = vec2(1.0, 0.0);
    for (int k = 1; k <= N; ++k) t[k] = vec2(b[2 * k - 2], b[2 * k - 1]) / b0 * (1.0 - bias);
    // 1. T = L D L^H, T_ij = t_(i-j) below the diagonal, the order cut where D_jj <= bias.
    vec2 L[N + 1][N + 1];
    float D[N + 1], inv_d[N + 1];
    for (int i = 0; i <= N; ++i)  // every entry written (a compiler warning is a GL error here)
        for (int j = 0; j <= N; ++j) L[i][j] = vec2(0.0);
    int order = N;
    for (int j = 0; j <= N; ++j) {
        float d = 1.0;
        for (int k = 0; k < j; ++k) d -= dot(L[j][k], L[j][k]) * D[k];
        if (j > 0 && order == N && !(d > kMboitKeep * bias)) order = j - 1;
        D[j] = j <= order ? d : 1.0;
        inv_d[j] = j <= order ? 1.0 / d : 0.0;
        for (int i = j + 1; i <= N; ++i) {
            vec2 e = t[i - j];
            for (int k = 0; k < j; ++k) e -= mboit_cmul(L[i][k], mboit_conj(L[j][k])) * D[k];
            L[i][j] = e / D[j];
        }
    }
    if (order == 0) return clamp(exp(-b0 * beta), 0.0, 1.0);  // one depth
    // 2. T_k c = v(x0), then the kernel polynomial q(x) = sum conj(c_j) x^j.
    float phi0 = mboit_phase(z0);
    vec2 x0 = vec2(cos(phi0), sin(phi0));
    vec2 c[N + 1], xk = vec2(1.0, 0.0);
    for (int i = 0; i <= N; ++i) c[i] = vec2(0.0);
    for (int i = 0; i <= N; ++i) {
        vec2 y = xk;
        for (int k = 0; k < i; ++k) y -= mboit_cmul(L[i][k], c[k]);
        c[i] = y;
        xk = mboit_cmul(xk, x0);
    }
    for (int i = 0; i <= N; ++i) c[i] *= inv_d[i];
    for (int i = N; i >= 0; --i)
        for (int k = i + 1; k <= N; ++k) c[i] -= mboit_cmul(mboit_conj(L[k][i]), c[k]);
    // Monic q: a_j = conj(c_j) / conj(c_order); roots by Durand-Kerner from spread points.
    vec2 a[N + 1], lead = mboit_conj(c[0]);
    for (int j = 0; j <= N; ++j) {
        if (j == order) lead = mboit_conj(c[j]);
    }
    for (int j = 0; j <= N; ++j) a[j] = j <= order ? mboit_cdiv(mboit_conj(c[j]), lead) : vec2(0.0);
    vec2 r[N];
    for (int i = 0; i < N; ++i) {
        float ang = 0.4 + 6.2831853 * float(i) / float(max(order, 1));
        r[i] = vec2(cos(ang), sin(ang));
    }
    for (int it = 0; it < 16; ++it) {
        for (int i = 0; i < N; ++i) {
            vec2 v = vec2(1.0, 0.0);  // q(r_i), Horner from the monic top
            for (int j = N - 1; j >= 0; --j)
                if (j < order) v = mboit_cmul(v, r[i]) + a[j];
            vec2 den = vec2(1.0, 0.0);
            for (int j = 0; j < N; ++j)
                if (j != i && j < order) den = mboit_cmul(den, r[i] - r[j]);
            if (i < order && dot(den, den) > 0.0) r[i] -= mboit_cdiv(v, den);
        }
    }
    // 3. The weights: x0 with beta, each root 1 in front, 0 behind, a ramp across the zone.
    float wsum = 0.0, share = 0.0;
    for (int s = 0; s <= N; ++s) {
        vec2 x = s == 0 ? x0 : normalize(r[max(s - 1, 0)]);
        vec2 y[N + 1], xp = vec2(1.0, 0.0);
        for (int i = 0; i <= N; ++i) y[i] = vec2(0.0);
        float k = 0.0;
        for (int i = 0; i <= N; ++i) {
            vec2 v = xp;
            for (int j = 0; j < i; ++j) v -= mboit_cmul(L[i][j], y[j]);
            y[i] = v;
            k += dot(v, v) * inv_d[i];
            xp = mboit_cmul(xp, x);
        }
        float ang = atan(x.y, x.x);
        ang = ang < 0.0 ? ang + 6.2831853 : ang;
        float f = s == 0 ? beta
                         : (ang < phi0 ? 1.0 : 0.0) + clamp((ang - 2.0 * kMboitPhaseScale) / kMboitWrapZone, 0.0, 1.0);
        float w = s <= order ? 1.0 / k : 0.0;
        wsum += w;
        share += w * f;
    }
    share /= wsum;
    if (isnan(share) || isinf(share)) share = beta;
    return clamp(exp(-b0 * share), 0.0, 1.0);
}
#elif MBOIT_ORDER == 2
// 4 moments, the steps below written out for n = 2 (the general loop's arrays made llvmpipe's
// accum 2.5x as slow, 49 against 19 ms on the small phantom). Their results agree.
float mboit_weight2(float x, float m1, float m2, float l21, float inv_d1, float inv_d2) {
    float y1 = x - m1, y2 = x * x - m2 - l21 * y1;
    return 1.0 / (1.0 + y1 * y1 * inv_d1 + y2 * y2 * inv_d2);
}
float mboit_transmittance(float b0, float b[8], float z0, float bias, float beta) {
    if (b0 <= 1e-6) return 1.0;
    vec4 m = mix(vec4(b[0], b[1], b[2], b[3]) / b0, vec4(0.0, 1.0 / 3.0, 0.0, 1.0 / 5.0), bias);
    float d1 = m.y - m.x * m.x;
    // D_11 at the floor: one depth, at z = 0 (anywhere else it lies above; see step 1).
    if (!(d1 > kMboitKeep * bias * kMboitUniformD[1])) return clamp(exp(-b0 * beta), 0.0, 1.0);
    float inv_d1 = 1.0 / d1;
    float l21 = (m.z - m.x * m.y) * inv_d1;
    float d2 = (m.w - m.y * m.y) - l21 * l21 * d1;
    float y1 = z0 - m.x, y2 = z0 * z0 - m.y - l21 * y1;
    float z1, z2 = 0.0, w1, w2 = 0.0, inv_d2 = 0.0;
    if (d2 > kMboitKeep * bias * kMboitUniformD[2]) {
        inv_d2 = 1.0 / d2;
        float c2 = y2 * inv_d2, c1 = y1 * inv_d1 - l21 * c2, c0 = 1.0 - m.x * c1 - m.y * c2;
        mboit_quadratic_roots(c2, c1, c0, z1, z2);
        w2 = mboit_weight2(z2, m.x, m.y, l21, inv_d1, inv_d2);
    } else {  // two depths: the linear kernel's root
        float c1 = y1 * inv_d1;
        z1 = -(1.0 - m.x * c1) / c1;
    }
    w1 = mboit_weight2(z1, m.x, m.y, l21, inv_d1, inv_d2);
    float w0 = mboit_weight2(z0, m.x, m.y, l21, inv_d1, inv_d2);
    float share = (beta * w0 + (z1 < z0 ? w1 : 0.0) + (z2 < z0 ? w2 : 0.0)) / (w0 + w1 + w2);
    if (isnan(share) || isinf(share)) share = beta;
    return clamp(exp(-b0 * share), 0.0, 1.0);
}
#else
float mboit_transmittance(float b0, float b[8], float z0, float bias, float beta) {
    if (b0 <= 1e-6) return 1.0;
    // Every loop has a constant bound and every index is constant once unrolled (a loop cut at
    // a run-time bound left the arrays in memory: llvmpipe's accum took 3x as long); what lies
    // beyond the order is masked by inv_d = 0.
    const int N = kMboitN;
    float m[2 * N + 1];
    m[0] = 1.0;
    for (int k = 1; k <= 2 * N; ++k) m[k] = mix(b[k - 1] / b0, (k & 1) == 0 ? 1.0 / float(k + 1) : 0.0, bias);
    // 1. H = L D L^T (unit lower L; column 0 of L is m_i), the order cut where D_jj is noise
    // (beyond it D counts as 1 and 1 / D as 0).
    float L[N + 1][N + 1], D[N + 1], inv_d[N + 1];
    D[0] = inv_d[0] = 1.0;
    int order = N;
    for (int i = 0; i <= N; ++i)  // every entry written (a compiler warning is a GL error here)
        for (int j = 0; j <= N; ++j) L[i][j] = j == 0 ? m[i] : 0.0;
    for (int j = 1; j <= N; ++j) {
        float d = m[2 * j];
        for (int k = 0; k < j; ++k) d -= L[j][k] * L[j][k] * D[k];
        if (order == N && !(d > kMboitKeep * bias * kMboitUniformD[j])) order = j - 1;
        D[j] = j <= order ? d : 1.0;
        inv_d[j] = j <= order ? 1.0 / d : 0.0;
        for (int i = j + 1; i <= N; ++i) {
            float e = m[i + j];
            for (int k = 0; k < j; ++k) e -= L[i][k] * L[j][k] * D[k];
            L[i][j] = e / D[j];
        }
    }
    // 2. H_k c = (1, z0, .., z0^k) by forward, diagonal and backward substitution.
    float c[5] = float[5](0.0, 0.0, 0.0, 0.0, 0.0);
    float zk = 1.0;
    for (int i = 0; i <= N; ++i) {
        float y = zk;
        for (int k = 0; k < i; ++k) y -= L[i][k] * c[k];
        c[i] = y;
        zk *= z0;
    }
    for (int i = 0; i <= N; ++i) c[i] *= inv_d[i];
    for (int i = N; i >= 0; --i)
        for (int k = i + 1; k <= N; ++k) c[i] -= L[k][i] * c[k];
    // The kernel polynomial's roots: the support points beside z0.
    float z[5] = float[5](z0, 0.0, 0.0, 0.0, 0.0);
    if (order == 1) {
        z[1] = -c[0] / c[1];
    } else if (order == 2) {
        mboit_quadratic_roots(c[2], c[1], c[0], z[1], z[2]);
    } else if (order == 3) {
        float r[3];
        mboit_cubic_roots(c[2] / c[3], c[1] / c[3], c[0] / c[3], r);
        z[1] = r[0], z[2] = r[1], z[3] = r[2];
    } else if (order == 4) {
        float r[4];
        mboit_quartic_roots(c[3] / c[4], c[2] / c[4], c[1] / c[4], c[0] / c[4], r);
        z[1] = r[0], z[2] = r[1], z[3] = r[2], z[4] = r[3];
    }
    if (order >= 3) {  // closed forms lose digits to cancellation: two Newton steps each
        for (int i = 1; i <= N; ++i) {
            for (int it = 0; it < 2; ++it) {
                float dp = mboit_horner_d(c, z[i]);
                if (i <= order && dp != 0.0) z[i] -= mboit_horner(c, z[i]) / dp;
            }
        }
    }
    // 3. The support points' weights 1 / K(z_i, z_i), K(x, x) = sum_j y_j^2 / D_jj with
    // L y = (1, x, .., x^k).
    float wsum = 0.0, share = 0.0;
    for (int s = 0; s <= N; ++s) {
        float x = z[s], xk = 1.0, y[N + 1], k = 0.0;
        for (int i = 0; i <= N; ++i) y[i] = 0.0;
        for (int i = 0; i <= N; ++i) {
            float v = xk;
            for (int j = 0; j < i; ++j) v -= L[i][j] * y[j];
            y[i] = v;
            k += v * v * inv_d[i];
            xk *= x;
        }
        float w = s <= order ? 1.0 / k : 0.0;
        wsum += w;
        share += w * (s == 0 ? beta : (x < z0 ? 1.0 : 0.0));
    }
    share /= wsum;  // the weights sum to 1 in exact arithmetic
    // A reconstruction that still broke down (not seen in the tests) falls back to beta.
    if (isnan(share) || isinf(share)) share = beta;
    return clamp(exp(-b0 * share), 0.0, 1.0);
}
#endif  // MBOIT_ORDER
#endif
