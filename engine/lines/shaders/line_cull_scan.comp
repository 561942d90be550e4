#version 450 core
// The line kit's GPU culling: where each chunk drawn in a phase puts its segments in the index
// buffer (an exclusive prefix sum of their counts in chunk order, so the draw order is the
// unculled draw's and the same every run), the phase's draw command and the frame's counts.
// Any number of chunks, block-wise (engine/lines/src/cull_scan.hpp runs the levels): a block is
// CULL_SCAN_BLOCK values, CULL_SCAN_PER_THREAD consecutive ones per invocation.
//   reduce  (u_cull_reduce = 1) each block's sum into the level above (the header's scratch);
//   scan    the top level (one block) from the phase's base, then each level below from the
//           offset its block got above: every value's exclusive prefix, in place, and at
//           level 0 each drawn chunk's offset. Level 0's scan also counts the chunk flags.
#define CULL_USES_STATE
#define CULL_USES_HEADER
#include "line_cull.glsl"

layout(local_size_x = CULL_SCAN_THREADS) in;

const uint kThreads = uint(CULL_SCAN_THREADS);
const uint kPer = uint(CULL_SCAN_PER_THREAD);
const uint kBlock = kThreads * kPer;
const uint kTop = 0xffffffffu;

uniform uint u_cull_count;  // values at this level (level 0: the chunks)
uniform uint u_cull_in;     // level > 0: where its values lie in the scratch (uints)
uniform uint u_cull_out;    // reduce: where the block sums go; scan: where the blocks' offsets are (kTop: none, the top)
uniform int u_cull_level0;  // 1: the values are the chunks' segments in this phase
uniform int u_cull_reduce;  // 1: block sums only
uniform int u_cull_phase;   // 1 or 2

shared uint s_sum[CULL_SCAN_THREADS];
shared uint s_chunks, s_outside, s_drawn, s_occluded;

uint phase_bit() { return u_cull_phase == 1 ? kCullPhase1 : kCullPhase2; }

uint value(uint i) {
    if (i >= u_cull_count) return 0u;
    if (u_cull_level0 == 0) return cull_header[uint(CULL_H_SCRATCH) + u_cull_in + i];
    return (cull_state[i].flags & phase_bit()) != 0u ? cull_state[i].count : 0u;
}

void main() {
    uint t = gl_LocalInvocationID.x, g = gl_WorkGroupID.x;
    uint first = g * kBlock + t * kPer;
    bool counting = u_cull_level0 != 0 && u_cull_reduce == 0;
    if (t == 0u) s_chunks = 0u, s_outside = 0u, s_drawn = 0u, s_occluded = 0u;
    uint v[kPer];
    uint sum = 0u, chunks = 0u, outside = 0u, drawn = 0u, occluded = 0u;
    for (uint k = 0u; k < kPer; ++k) {
        v[k] = value(first + k);
        sum += v[k];
        if (counting && first + k < u_cull_count) {
            uint f = cull_state[first + k].flags;
            drawn += (f & phase_bit()) != 0u ? 1u : 0u;
            chunks += (f & kCullDrawn) != 0u ? 1u : 0u;
            outside += (f & kCullOutside) != 0u ? 1u : 0u;
            occluded += (f & kCullOccluded) != 0u ? 1u : 0u;
        }
    }
    s_sum[t] = sum;
    barrier();
    if (counting) {
        atomicAdd(s_chunks, chunks);
        atomicAdd(s_outside, outside);
        atomicAdd(s_drawn, drawn);
        atomicAdd(s_occluded, occluded);
    }
    // Inclusive scan of the invocations' sums (Hillis-Steele).
    for (uint d = 1u; d < kThreads; d <<= 1u) {
        uint add = t >= d ? s_sum[t - d] : 0u;
        barrier();
        s_sum[t] += add;
        barrier();
    }
    // Phase 2's segments follow phase 1's in the index buffer.
    uint base = u_cull_phase == 1 ? 0u : cull_header[CULL_H_SEGMENTS];
    bool top = u_cull_out == kTop;
    if (u_cull_reduce != 0) {
        if (t == kThreads - 1u) cull_header[uint(CULL_H_SCRATCH) + u_cull_out + g] = s_sum[t];
    } else {
        uint at = (top ? base : cull_header[uint(CULL_H_SCRATCH) + u_cull_out + g]) + s_sum[t] - sum;
        for (uint k = 0u; k < kPer && first + k < u_cull_count; ++k) {
            if (u_cull_level0 == 0) cull_header[uint(CULL_H_SCRATCH) + u_cull_in + first + k] = at;
            else if ((cull_state[first + k].flags & phase_bit()) != 0u) cull_state[first + k].offset = at;
            at += v[k];
        }
        if (top && t == kThreads - 1u) {
            uint total = s_sum[t];
            uint cmd = uint(CULL_H_CMD) + 5u * uint(u_cull_phase - 1);
            cull_header[cmd + 0u] = 2u * total;  // GL_LINES: two indices a segment
            cull_header[cmd + 1u] = 1u;
            cull_header[cmd + 2u] = 2u * base;
            cull_header[cmd + 3u] = 0u;
            cull_header[cmd + 4u] = 0u;
            cull_header[uint(CULL_H_SEGMENTS) + uint(u_cull_phase - 1)] = total;
        }
    }
    // The group's counts into the frame's (CullScan clears them before phase 1).
    barrier();
    if (counting && t == 0u) {
        atomicAdd(cull_header[uint(CULL_H_DRAWN) + uint(u_cull_phase - 1)], s_drawn);
        if (u_cull_phase == 1) {
            atomicAdd(cull_header[CULL_H_CHUNKS], s_chunks);
            atomicAdd(cull_header[CULL_H_OUTSIDE], s_outside);
        } else {
            atomicAdd(cull_header[CULL_H_OCCLUDED], s_occluded);
        }
    }
}
