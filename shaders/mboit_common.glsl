// Moment-based OIT (mboit_moments, mboit_accum): what both passes must agree on, said once.
#ifndef PATHLET_MBOIT_COMMON_GLSL
#define PATHLET_MBOIT_COMMON_GLSL

// A fragment counts as at most this opaque: its absorbance stays finite (ln 10^4 = 9.2).
const float kMboitMaxAlpha = 0.9999;

float mboit_alpha(float alpha) { return min(alpha, kMboitMaxAlpha); }
float mboit_absorbance_of(float alpha) { return -log(1.0 - mboit_alpha(alpha)); }

// Trigonometric moments (moment_form trig2..trig4): the warped depth z in [-1, 1] as the point
// e^(i phi) of the unit circle, phi = (z + 1)(pi - w/2) in [0, 2 pi - w]. The arc of w left
// over is the wrapping zone, where a reconstructed support point is ambiguous between the
// nearest and the farthest depth (Peters et al.'s trigonometric moment shadow maps and
// MBOIT: 0.1 pi, as the paper and LineVis' computeWrappingZoneParameters).
const float kMboitWrapZone = 0.1 * 3.14159265;
const float kMboitPhaseScale = 3.14159265 - 0.5 * kMboitWrapZone;
float mboit_phase(float z) { return (z + 1.0) * kMboitPhaseScale; }
vec2 mboit_circle(float z) { float phi = mboit_phase(z); return vec2(cos(phi), sin(phi)); }
vec2 mboit_cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }

#endif
