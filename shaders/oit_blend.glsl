// What the blend-only and bounded-memory OIT passes (wboit_accum, mboit_moments, mboit_accum,
// mlab_bucket, mlab_blend) share beyond oit_fragment.glsl's fragment: the log-depth warp of
// moment-based OIT and, with CORE_AO, the opaque core's AO applied per fragment as resolve_list
// applies it (variant2_*_ao). Include after line_common.glsl.
#ifndef PATHLET_OIT_BLEND_GLSL
#define PATHLET_OIT_BLEND_GLSL

// The fragment every technique composites (oit_fragment_rgba, oit_fragment_visible).
#include "oit_fragment.glsl"

// The view depth of the fragment (the halo's push-back included) warped logarithmically to
// [-1, 1] between the camera's near and far planes: moments of a log depth spend their
// precision where a perspective view puts its detail (Münstermann et al. 2018, sec. 5).
float oit_log_depth(LineFrag f) {
    float near = max(u_depth_range.x, 1e-6), far = max(u_depth_range.y, near * 1.0001);
    float eye = mix(near, far, f.depth01);
    return 2.0 * log(eye / near) / log(far / near) - 1.0;
}

#ifdef CORE_AO
uniform sampler2D u_ao;        // the core's smoothed AO (bilateral's ao_smooth), a pin
uniform sampler2D u_core;      // the core's normal + linear depth (w), a pin
uniform float u_ao_tolerance;  // a parameter: linear depth within which a fragment is the core
// The colour lit by the core's AO where the fragment is the core surface; faded fragments in
// front of it and fragments behind it stay unoccluded.
vec3 oit_core_ao(vec3 rgb, LineFrag f) {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float core = texelFetch(u_core, p, 0).w;
    return abs(f.depth01 - core) <= u_ao_tolerance ? rgb * texelFetch(u_ao, p, 0).r : rgb;
}
#else
vec3 oit_core_ao(vec3 rgb, LineFrag f) { return rgb; }
#endif

#endif
