// Speed colour maps for line passes. `which` follows the `colormap` enum of the line passes:
// 0 green_red (the study: green slow -> yellow -> red fast), 1 viridis, 2 coolwarm, 3 grey,
// 4 direction (not a map of speed: the line kit colours by the tangent, colormap_direction),
// 5 bundle (not a map of speed either: a colour per bundle, the data file a line came from).
// u is the normalised speed in [0,1]; values outside are clamped.
#ifndef PATHLET_COLORMAP_GLSL
#define PATHLET_COLORMAP_GLSL

const int COLORMAP_GREEN_RED = 0;
const int COLORMAP_VIRIDIS = 1;
const int COLORMAP_COOLWARM = 2;
const int COLORMAP_GREY = 3;
const int COLORMAP_DIRECTION = 4;
const int COLORMAP_BUNDLE = 5;

// Direction colouring (tractography's convention): RGB = |dx|, |dy|, |dz| of the unit
// tangent in world (data) axes, so x runs red, y green, z blue whichever way a line goes.
vec3 colormap_direction(vec3 world_tangent) { return abs(normalize(world_tangent)); }

bool colormap_is_direction(int which) {
#ifdef LINE_COLORMAP
    which = LINE_COLORMAP;  // folds away in the line kit's specialised programs
#endif
    return which == COLORMAP_DIRECTION;
}

bool colormap_is_bundle(int which) {
#ifdef LINE_COLORMAP
    which = LINE_COLORMAP;
#endif
    return which == COLORMAP_BUNDLE;
}

// Bundle colours: matplotlib's tab10 (Tableau's categorical palette), in its order; bundle k
// takes entry k mod 10. The legend's swatches read the same entries (overlay.frag).
const int BUNDLE_PALETTE_SIZE = 10;
const vec3 BUNDLE_PALETTE[BUNDLE_PALETTE_SIZE] = vec3[BUNDLE_PALETTE_SIZE](
    vec3(0.121569, 0.466667, 0.705882), vec3(1.000000, 0.498039, 0.054902), vec3(0.172549, 0.627451, 0.172549),
    vec3(0.839216, 0.152941, 0.156863), vec3(0.580392, 0.403922, 0.741176), vec3(0.549020, 0.337255, 0.294118),
    vec3(0.890196, 0.466667, 0.760784), vec3(0.498039, 0.498039, 0.498039), vec3(0.737255, 0.741176, 0.133333),
    vec3(0.090196, 0.745098, 0.811765));
vec3 colormap_bundle(uint k) { return BUNDLE_PALETTE[k % uint(BUNDLE_PALETTE_SIZE)]; }

// Green -> yellow -> red through saturated mid tones (no muddy olive in the middle).
vec3 colormap_green_red(float u) {
    const vec3 green = vec3(0.10, 0.70, 0.20);
    const vec3 yellow = vec3(0.98, 0.85, 0.10);
    const vec3 red = vec3(0.85, 0.10, 0.10);
    return u < 0.5 ? mix(green, yellow, u * 2.0) : mix(yellow, red, u * 2.0 - 1.0);
}

// Polynomial fit of matplotlib's viridis (max error well under one 8-bit step).
vec3 colormap_viridis(float u) {
    const vec3 c0 = vec3(0.2777273272234177, 0.005407344544966578, 0.3340998053353061);
    const vec3 c1 = vec3(0.1050930431085774, 1.404613529898575, 1.384590162594685);
    const vec3 c2 = vec3(-0.3308618287255563, 0.214847559468213, 0.09509516302823659);
    const vec3 c3 = vec3(-4.634230498983486, -5.799100973351585, -19.33244095627987);
    const vec3 c4 = vec3(6.228269936347081, 14.17993336680509, 56.69055260068105);
    const vec3 c5 = vec3(4.776384997670288, -13.74514537774601, -65.35303263337234);
    const vec3 c6 = vec3(-5.435455855934631, 4.645852612178535, 26.3124352495832);
    return clamp(c0 + u * (c1 + u * (c2 + u * (c3 + u * (c4 + u * (c5 + u * c6))))), 0.0, 1.0);
}

// Moreland's diverging cool-warm map, piecewise linear through five of its control points.
vec3 colormap_coolwarm(float u) {
    const vec3 k0 = vec3(0.230, 0.299, 0.754);
    const vec3 k1 = vec3(0.553, 0.690, 0.996);
    const vec3 k2 = vec3(0.865, 0.865, 0.865);
    const vec3 k3 = vec3(0.957, 0.598, 0.477);
    const vec3 k4 = vec3(0.706, 0.016, 0.150);
    float x = u * 4.0;
    if (x < 1.0) return mix(k0, k1, x);
    if (x < 2.0) return mix(k1, k2, x - 1.0);
    if (x < 3.0) return mix(k2, k3, x - 2.0);
    return mix(k3, k4, x - 3.0);
}

vec3 colormap(int which, float u) {
    u = clamp(u, 0.0, 1.0);
#ifdef LINE_COLORMAP
    which = LINE_COLORMAP;  // the line kit compiles one map per program (the branches fold away)
#endif
    if (which == COLORMAP_VIRIDIS) return colormap_viridis(u);
    if (which == COLORMAP_COOLWARM) return colormap_coolwarm(u);
    // Grey stays off pure black and white so lines read on either background.
    if (which == COLORMAP_GREY) return vec3(mix(0.25, 0.9, u));
    return colormap_green_red(u);
}

#endif
