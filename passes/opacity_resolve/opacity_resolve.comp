#version 450 core
// opacity_resolve: per pixel of opacity_lists' lists, the fragments sorted front to back (ties
// by segment) and the decoupled closed form of Günther, Theisel, Gross 2017 (Algorithm 1):
//   alpha_i = p / (p + (1 - g_i)^(2 lambda) (r F_i + q B_i)),  p = 1,
// with F_i and B_i the summed squared importance in front of and behind fragment i. Each
// segment keeps the least opacity any of its fragments asked for (an atomic minimum of the
// float bits, which order like the floats for opacities >= 0); the first fragment of a segment
// also puts the segment on the list opacity_blend works through.
layout(local_size_x = 8, local_size_y = 8) in;

#include "opacity_optimization.glsl"

layout(std430, binding = LISTS_BINDING) readonly buffer OoLists { uint oo_list[]; };
layout(std430, binding = SEGMENTS_BINDING) readonly buffer OoSegments { uint oo_seg[]; };
layout(std430, binding = TARGETS_BINDING) coherent buffer OoTargets { uint oo_target[]; };

uniform float u_q;       // occlusion: important fragments behind must show
uniform float u_r;       // clutter: important fragments in front must not be cluttered
uniform float u_lambda;  // importance shields itself: (1 - g)^(2 lambda)

#define K MAX_FRAGMENTS  // the nearest fragments that get an opacity (compiled in)

bool nearer(float d, uint s, float d2, uint s2) { return d < d2 || (d == d2 && s < s2); }

void main() {
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
        float alpha = 1.0 / (1.0 + pow(1.0 - g, 2.0 * u_lambda) * (u_r * F + u_q * B));
        F += g2;
        uint old = atomicMin(oo_target[OO_TARGET_ALPHA + seg[k]], floatBitsToUint(alpha));
        if (old == OO_UNSEEN) {  // the segment's first fragment this frame: on the work list
            uint at = atomicAdd(oo_target[OO_TARGET_COUNT], 1u);
            oo_target[OO_TARGET_ALPHA + segments + at] = seg[k];
            atomicMax(oo_target[OO_TARGET_GROUPS], at / OO_GROUP + 1u);
        }
    }
}
