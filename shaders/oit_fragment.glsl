// A line fragment as every transparency technique composites it (fill_list's lists, depth
// peeling, the approximations), so they all blend the same fragments: the colour hook's
// colour with the kit's halo tint, and its opacity times the analytic edge coverage
// (line_coverage: a pixel at a rim or an end is as opaque as the share of it the quad covers, a
// line thinner than a pixel no more than its width). Include after line_common.glsl.
#ifndef PATHLET_OIT_FRAGMENT_GLSL
#define PATHLET_OIT_FRAGMENT_GLSL

vec4 oit_fragment_rgba(LineFrag f, vec4 hooked) {
    return vec4(line_halo_tint(hooked.rgb, f), hooked.a * line_coverage(f));
}
// Below half an 8-bit level a fragment shows nothing: no technique stores or peels it.
bool oit_fragment_visible(float alpha) { return alpha >= 0.5 / 255.0; }

#endif
