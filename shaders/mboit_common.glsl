// Moment-based OIT (mboit_moments, mboit_accum): what both passes must agree on, said once.
#ifndef PATHLET_MBOIT_COMMON_GLSL
#define PATHLET_MBOIT_COMMON_GLSL

// A fragment counts as at most this opaque: its absorbance stays finite (ln 10^4 = 9.2).
const float kMboitMaxAlpha = 0.9999;

float mboit_alpha(float alpha) { return min(alpha, kMboitMaxAlpha); }
float mboit_absorbance_of(float alpha) { return -log(1.0 - mboit_alpha(alpha)); }

#endif
