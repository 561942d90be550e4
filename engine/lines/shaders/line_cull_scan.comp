#version 450 core
// The line kit's GPU culling: where each chunk drawn in a phase puts its segments in the index
// buffer (an exclusive prefix sum of their counts in chunk order, so the draw order is the
// unculled draw's and the same every run), the phase's draw command and the frame's counts.
// Any number of chunks, block-wise (engine/lines/src/cull_scan.hpp runs the levels): a block is
// CULL_SCAN_THREADS x CULL_SCAN_PER_THREAD values, CULL_SCAN_PER_THREAD consecutive ones per
// invocation.
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
const uint kRun = 16u;  // kThreads = kRun * kRun
#if CULL_SCAN_THREADS != 256
#error "line_cull_scan.comp scans 16 runs of 16 invocations"
#endif

uniform uint u_cull_count;  // values at this level (level 0: the chunks)
uniform uint u_cull_in;     // level > 0: where its values lie in the scratch (uints)
uniform uint u_cull_out;    // reduce: where the block sums go; scan: where the blocks' offsets are (kTop: none, the top)
uniform int u_cull_level0;  // 1: the values are the chunks' segments in this phase
uniform int u_cull_reduce;  // 1: block sums only
uniform int u_cull_phase;   // 1 or 2

shared uint s_sum[CULL_SCAN_THREADS];
shared uint s_run[16];
shared uint s_chunks, s_outside, s_drawn, s_occluded;

uint phase_bit() { return u_cull_phase == 1 ? kCullPhase1 : kCullPhase2; }

void main() {
    uint t = gl_LocalInvocationID.x, g = gl_WorkGroupID.x;
    uint first = g * kBlock + t * kPer;
    bool counting = u_cull_level0 != 0 && u_cull_reduce == 0;
    uint bit = phase_bit();
    if (t == 0u) s_chunks = 0u, s_outside = 0u, s_drawn = 0u, s_occluded = 0u;
    // Each value and chunk flag read once (llvmpipe pays for every storage load).
    uint v[kPer], flags[kPer];
    uint sum = 0u, chunks = 0u, outside = 0u, drawn = 0u, occluded = 0u;
    for (uint k = 0u; k < kPer; ++k) {
        uint i = first + k;
        flags[k] = 0u;
        v[k] = 0u;
        if (i < u_cull_count) {
            if (u_cull_level0 == 0) {
                v[k] = cull_header[uint(CULL_H_SCRATCH) + u_cull_in + i];
            } else {
                flags[k] = cull_state[i].flags;
                if ((flags[k] & bit) != 0u) v[k] = cull_state[i].count;
            }
        }
        sum += v[k];
        drawn += (flags[k] & bit) != 0u ? 1u : 0u;
        chunks += (flags[k] & kCullDrawn) != 0u ? 1u : 0u;
        outside += (flags[k] & kCullOutside) != 0u ? 1u : 0u;
        occluded += (flags[k] & kCullOccluded) != 0u ? 1u : 0u;
    }
    s_sum[t] = sum;
    barrier();
    if (counting) {
        atomicAdd(s_chunks, chunks);
        atomicAdd(s_outside, outside);
        atomicAdd(s_drawn, drawn);
        atomicAdd(s_occluded, occluded);
    }
    // Inclusive scan of the invocations' sums in kRun runs of kRun: the first kRun invocations
    // each scan a run, the first scans the runs' totals, then each adds its run's carry. Three
    // barriers, not Hillis-Steele's 16: llvmpipe pays per barrier and invocation, and on a GPU
    // 48 dependent shared-memory steps a group are a microsecond.
    if (t < kRun) {
        uint acc = 0u;
        for (uint i = 0u; i < kRun; ++i) acc += s_sum[t * kRun + i], s_sum[t * kRun + i] = acc;
        s_run[t] = acc;
    }
    barrier();
    if (t == 0u) {
        uint acc = 0u;
        for (uint i = 0u; i < kRun; ++i) {
            uint run = s_run[i];
            s_run[i] = acc;  // what the runs before it add up to
            acc += run;
        }
    }
    barrier();
    s_sum[t] += s_run[t / kRun];  // only invocation t reads s_sum[t] from here on
    // Phase 2's segments follow phase 1's in the index buffer.
    uint base = u_cull_phase == 1 ? 0u : cull_header[CULL_H_SEGMENTS];
    bool top = u_cull_out == kTop;
    if (u_cull_reduce != 0) {
        if (t == kThreads - 1u) cull_header[uint(CULL_H_SCRATCH) + u_cull_out + g] = s_sum[t];
    } else {
        uint at = (top ? base : cull_header[uint(CULL_H_SCRATCH) + u_cull_out + g]) + s_sum[t] - sum;
        for (uint k = 0u; k < kPer && first + k < u_cull_count; ++k) {
            if (u_cull_level0 == 0) cull_header[uint(CULL_H_SCRATCH) + u_cull_in + first + k] = at;
            else if ((flags[k] & bit) != 0u) cull_state[first + k].offset = at;
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
