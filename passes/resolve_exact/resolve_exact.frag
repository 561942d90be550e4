#version 450 core
// resolve_exact: every fragment of the pixel's list, composited front to back by depth until
// the transmittance left is below u_min_transmittance; the fragments at one depth are one layer,
// composited together (oit_depth_group.glsl: the rule depth_peel follows too). No fragment cap:
// the list is sorted in rounds of a bounded local array (a block of K), as register/block sorts
// do (Knowles et al. 2014), in the lists' total order (oit_nearer, then the node index): each
// round walks the list and keeps, by insertion, the K nearest fragments after the last one
// taken; a round that finds fewer than K was the last. Registers: K. A layer may run on into the
// next round: it is composited once a deeper fragment (or the list's end) closes it.
//
// Work per invocation is bounded too (drivers cut or time out long shader loops; llvmpipe ends
// one silently): a draw stops a pixel after u_visit_budget node visits and carries its state
// (colour so far, transmittance, the open layer, the last fragment taken) to the next draw in
// images; the pass draws again while pixels are pending. Only a single walk longer than the
// budget is cut, and a cut pixel is counted (its frame is reported incomplete).
#include "oit_list.glsl"
#include "oit_depth_group.glsl"

#define K SORT_BLOCK
#define OIT_BLOCK K
#define MAX_WALK 0x1000000u  // only a corrupt (cyclic) list is longer: then the pixel is counted

#define STATE_FRESH 0u
#define STATE_PENDING 1u
#define STATE_DONE 2u

layout(r32ui) uniform readonly uimage2D u_heads;  // the pins, by declaration
uniform usamplerBuffer u_nodes;                   // the pass's view of the `nodes` buffer
#include "oit_block_sort.glsl"
layout(rgba32f) uniform image2D u_carry;          // colour composited so far, transmittance left
layout(rgba32f) uniform image2D u_layer;          // the open layer (oit_layer_add); zero: none
layout(rgba32ui) uniform uimage2D u_last;         // the last fragment taken: depth bits, id, colour, node
layout(r32ui) uniform uimage2D u_state;           // STATE_*
layout(std430, binding = STATS_BINDING) buffer OitExactStats {
    uint peak_nodes;
    uint peak_rounds;
    uint cut_pixels;
    uint pending_pixels;  // left for the next draw
};
uniform float u_min_transmittance;
uniform vec3 u_background;
uniform int u_visit_budget;  // node visits per pixel and draw

layout(location = 0) out vec4 o_color;
// The coverage's depth test before the shader, although it writes images: pixels without
// fragments are skipped, never shaded (draw_fullscreen_on_geometry).
layout(early_fragment_tests) in;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    uint state = imageLoad(u_state, p).r;
    if (state == STATE_DONE) discard;  // finished in an earlier draw: its colour stays
    uint head = imageLoad(u_heads, p).r;
    if (head == OIT_END) {  // no fragment: the background
        imageStore(u_state, p, uvec4(STATE_DONE));
        o_color = vec4(u_background, 0.0);
        return;
    }
    // The last fragment taken (the round's threshold, and the open layer's depth); none before
    // the first round.
    bool first = state == STATE_FRESH;
    vec4 carry = first ? vec4(0.0, 0.0, 0.0, 1.0) : imageLoad(u_carry, p);
    vec4 layer = first ? vec4(0.0) : imageLoad(u_layer, p);
    uvec4 last = first ? uvec4(0u) : imageLoad(u_last, p);
    OitBlockAfter after = first ? kOitBlockStart : OitBlockAfter(true, uintBitsToFloat(last.x), last.y, last.z, last.w);
    vec3 rgb = carry.rgb;
    float t = carry.a;  // transmittance left
    float layer_depth = after.d;  // of the open layer (when it is not empty)
    uint len = 0u, rounds = 0u, visits = 0u;
    bool cut = false, finished = false;
    while (visits < uint(u_visit_budget)) {
        uint walked;
        bool cut_walk;
        int n = oit_sort_block(head, after, MAX_WALK, walked, cut_walk);
        cut = cut || cut_walk;
        if (rounds == 0u) len = walked;
        else if (walked != len) cut = true;  // the same list walked short: a loop cut by the driver
        visits += walked;
        ++rounds;
        for (int k = 0; k < n && t >= u_min_transmittance; ++k) {
            if (!oit_layer_empty(layer) && oit_block_dep[k] != layer_depth) {  // a deeper fragment closes the layer
                oit_layer_composite(rgb, t, layer);
                layer = vec4(0.0);
                if (t < u_min_transmittance) break;
            }
            layer = oit_layer_add(layer, unpackUnorm4x8(oit_block_col[k]));
            layer_depth = oit_block_dep[k];
        }
        if ((n < K || cut) && !oit_layer_empty(layer)) {  // the list's end closes the last layer (or a corrupt list ends it)
            oit_layer_composite(rgb, t, layer);
            layer = vec4(0.0);
        }
        if (t < u_min_transmittance || n < K || cut) {  // finished, every fragment seen, or a corrupt list
            finished = true;
            break;
        }
        after = oit_block_last();
    }
    // Plain reads first: the peaks only grow, so most pixels need no (contended) atomic.
    if (len > peak_nodes) atomicMax(peak_nodes, len);
    if (rounds > peak_rounds) atomicMax(peak_rounds, rounds);
    if (!finished && visits < uint(u_visit_budget)) cut = true;  // the loop ended otherwise: cut by the driver
    if (cut) atomicAdd(cut_pixels, 1u);
    if (!finished && !cut) {  // the budget is spent: the next draw goes on from here
        imageStore(u_carry, p, vec4(rgb, t));
        imageStore(u_layer, p, layer);
        imageStore(u_last, p, uvec4(floatBitsToUint(after.d), after.id, after.c, after.n));
        imageStore(u_state, p, uvec4(STATE_PENDING));
        atomicAdd(pending_pixels, 1u);
        discard;
    }
    imageStore(u_state, p, uvec4(STATE_DONE));
    // Alpha 1 wherever a fragment landed, as resolve_list's colour.
    o_color = vec4(rgb + t * u_background, 1.0);
}
