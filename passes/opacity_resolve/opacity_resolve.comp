#version 450 core
// opacity_resolve: per pixel of opacity_lists' lists, the fragments sorted front to back (ties
// by segment) and the decoupled closed form of Günther, Theisel, Gross 2017 (Algorithm 1):
//   alpha_i = p / (p + (1 - g_i)^(2 lambda) (r F_i + q B_i)),  p = 1,
// with F_i and B_i the summed squared importance in front of and behind fragment i. Each
// segment keeps the least opacity any of its fragments asked for (an atomic minimum of the
// float bits, which order like the floats for opacities >= 0); the first fragment of a segment
// also puts the segment on the list opacity_blend works through.
//
// adapt = depth_complexity: a first dispatch (OO_MEASURE) sums the lists' fragments and covered
// pixels into `density`; the resolve scales q and r by (D / depth_reference)^adapt_exponent,
// D the frame's mean depth complexity (fragments per covered pixel), read on the GPU.
layout(local_size_x = 8, local_size_y = 8) in;

#include "opacity_optimization.glsl"

layout(std430, binding = LISTS_BINDING) readonly buffer OoLists { uint oo_list[]; };
layout(std430, binding = SEGMENTS_BINDING) readonly buffer OoSegments { uint oo_seg[]; };
layout(std430, binding = TARGETS_BINDING) coherent buffer OoTargets { uint oo_target[]; };
layout(std430, binding = DENSITY_BINDING) coherent buffer OoDensity { uint oo_density[]; };

// The density's words: covered pixels and fragments (64 bits each: low, high), the scale used.
#define OO_DENSITY_PIXELS 0
#define OO_DENSITY_FRAGMENTS 2
#define OO_DENSITY_SCALE 4

#ifdef OO_MEASURE
// 64-bit sums from 32-bit atomics: the carry goes to the high word.
void add64(int at, uint v) {
    uint old = atomicAdd(oo_density[at], v);
    if (old > 0xFFFFFFFFu - v) atomicAdd(oo_density[at + 1], 1u);
}
shared uint s_pixels, s_fragments;  // the work group's share, one atomic each to the buffer

void main() {
    if (gl_LocalInvocationIndex == 0u) s_pixels = 0u, s_fragments = 0u;
    barrier();
    uvec2 p = gl_GlobalInvocationID.xy;
    uint w = oo_list[OO_LIST_WIDTH];
    if (p.x < w && p.y < oo_list[OO_LIST_HEIGHT]) {
        uint nodes = oo_nodes_at(oo_list), len = 0u;
        for (uint i = oo_list[OO_LIST_HEADS + p.y * w + p.x]; i != OO_END && len < 0x1000000u; ++len)
            i = oo_list[nodes + 4u * i + 3u];
        if (len > 0u) {
            atomicAdd(s_pixels, 1u);
            atomicAdd(s_fragments, len);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && s_pixels > 0u) {
        add64(OO_DENSITY_PIXELS, s_pixels);
        add64(OO_DENSITY_FRAGMENTS, s_fragments);
    }
}
#else

uniform float u_q;       // occlusion: important fragments behind must show
uniform float u_r;       // clutter: important fragments in front must not be cluttered
uniform float u_lambda;  // importance shields itself: (1 - g)^(2 lambda)
uniform int u_adapt;     // 0: depth_complexity, 1: fixed (the enum's order)
uniform float u_depth_reference, u_adapt_exponent, u_adapt_min, u_adapt_max;

float sum64(int at) { return float(oo_density[at]) + 4294967296.0 * float(oo_density[at + 1]); }

// The factor of q and r: 1 (fixed), or (D / depth_reference)^adapt_exponent within
// [adapt_min, adapt_max] for the frame's mean depth complexity D (no fragments: 1).
float clearing_scale() {
    if (u_adapt != 0) return 1.0;
    float pixels = sum64(OO_DENSITY_PIXELS);
    if (pixels <= 0.0) return 1.0;
    float depth = sum64(OO_DENSITY_FRAGMENTS) / pixels;
    return clamp(pow(depth / u_depth_reference, u_adapt_exponent), u_adapt_min, u_adapt_max);
}

#define K MAX_FRAGMENTS  // the nearest fragments that get an opacity (compiled in)

bool nearer(float d, uint s, float d2, uint s2) { return d < d2 || (d == d2 && s < s2); }

void main() {
    float scale = clearing_scale();
    if (gl_GlobalInvocationID.xy == uvec2(0u)) oo_density[OO_DENSITY_SCALE] = floatBitsToUint(scale);  // reported
    float q = u_q * scale, r = u_r * scale;
    uvec2 p = gl_GlobalInvocationID.xy;
    uint w = oo_list[OO_LIST_WIDTH];
    if (p.x >= w || p.y >= oo_list[OO_LIST_HEIGHT]) return;
    uint i = oo_list[OO_LIST_HEADS + p.y * w + p.x];
    if (i == OO_END) return;
    float dep[K], imp[K];
    uint seg[K];
    dep[K - 1] = 1.0, imp[K - 1] = 0.0, seg[K - 1] = 0u;
    uint nodes = oo_nodes_at(oo_list);
    int n = 0;
    uint len = 0u;
    float G = 0.0;  // over every fragment of the pixel, kept or not: all of them occlude
    while (i != OO_END && len < 0x1000000u) {  // the bound only guards against a corrupt list
        uint at = nodes + 4u * i;
        uint s = oo_list[at];
        float d = uintBitsToFloat(oo_list[at + 1u]), g = uintBitsToFloat(oo_list[at + 2u]);
        i = oo_list[at + 3u];
        ++len;
        G += g * g;
        if (n == K && !nearer(d, s, dep[K - 1], seg[K - 1])) continue;  // beyond the K kept
        int j = n < K ? n++ : K - 1;
        for (; j > 0 && nearer(d, s, dep[j - 1], seg[j - 1]); --j) {
            dep[j] = dep[j - 1];
            imp[j] = imp[j - 1];
            seg[j] = seg[j - 1];
        }
        dep[j] = d;
        imp[j] = g;
        seg[j] = s;
    }
    if (len > oo_target[OO_TARGET_PEAK]) atomicMax(oo_target[OO_TARGET_PEAK], len);
    if (len > uint(K)) {
        atomicAdd(oo_target[OO_TARGET_BEYOND], len - uint(K));
        atomicAdd(oo_target[OO_TARGET_TRUNCATED], 1u);
    }
    uint segments = oo_segments(oo_seg);
    float F = 0.0;
    for (int k = 0; k < n; ++k) {
        float g = imp[k], g2 = g * g;
        float B = max(G - F - g2, 0.0);
        float alpha = 1.0 / (1.0 + pow(1.0 - g, 2.0 * u_lambda) * (r * F + q * B));
        F += g2;
        uint old = atomicMin(oo_target[OO_TARGET_ALPHA + seg[k]], floatBitsToUint(alpha));
        if (old == OO_UNSEEN) {  // the segment's first fragment this frame: on the work list
            uint at = atomicAdd(oo_target[OO_TARGET_COUNT], 1u);
            oo_target[OO_TARGET_ALPHA + segments + at] = seg[k];
            atomicMax(oo_target[OO_TARGET_GROUPS], at / OO_GROUP + 1u);
        }
    }
}
#endif
