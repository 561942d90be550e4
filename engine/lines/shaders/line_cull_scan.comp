#version 450 core
// The line kit's GPU culling: where each chunk drawn in a phase puts its segments in the index
// buffer (an exclusive prefix sum of their counts in chunk order, so the draw order is the
// unculled draw's and the same every run), the phase's draw command and the frame's counts.
// One work group: each invocation sums a run of chunks, the group scans the sums, then each
// writes its run's offsets.
#define CULL_USES_STATE
#define CULL_USES_HEADER
#include "line_cull.glsl"

layout(local_size_x = CULL_SCAN_THREADS) in;

uniform uint u_cull_chunks;
uniform int u_cull_phase;  // 1 or 2

shared uint s_sum[CULL_SCAN_THREADS];
shared uint s_chunks, s_outside, s_drawn, s_occluded;

void main() {
    uint t = gl_LocalInvocationID.x;
    uint per = (u_cull_chunks + uint(CULL_SCAN_THREADS) - 1u) / uint(CULL_SCAN_THREADS);
    uint c0 = min(t * per, u_cull_chunks), c1 = min(c0 + per, u_cull_chunks);
    uint bit = u_cull_phase == 1 ? kCullPhase1 : kCullPhase2;
    if (t == 0u) s_chunks = 0u, s_outside = 0u, s_drawn = 0u, s_occluded = 0u;
    uint sum = 0u, chunks = 0u, outside = 0u, drawn = 0u, occluded = 0u;
    for (uint c = c0; c < c1; ++c) {
        uint f = cull_state[c].flags;
        if ((f & bit) != 0u) sum += cull_state[c].count, ++drawn;
        chunks += (f & kCullDrawn) != 0u ? 1u : 0u;
        outside += (f & kCullOutside) != 0u ? 1u : 0u;
        occluded += (f & kCullOccluded) != 0u ? 1u : 0u;
    }
    s_sum[t] = sum;
    barrier();
    atomicAdd(s_chunks, chunks);
    atomicAdd(s_outside, outside);
    atomicAdd(s_drawn, drawn);
    atomicAdd(s_occluded, occluded);
    // Inclusive scan of the sums (Hillis-Steele).
    for (uint d = 1u; d < uint(CULL_SCAN_THREADS); d <<= 1u) {
        uint add = t >= d ? s_sum[t - d] : 0u;
        barrier();
        s_sum[t] += add;
        barrier();
    }
    // Phase 2's segments follow phase 1's in the index buffer.
    uint base = u_cull_phase == 1 ? 0u : cull_header[CULL_H_SEGMENTS];
    uint at = base + s_sum[t] - sum;
    for (uint c = c0; c < c1; ++c) {
        if ((cull_state[c].flags & bit) != 0u) {
            cull_state[c].offset = at;
            at += cull_state[c].count;
        }
    }
    if (t == uint(CULL_SCAN_THREADS) - 1u) {
        uint total = s_sum[t];
        uint cmd = uint(CULL_H_CMD) + 5u * uint(u_cull_phase - 1);
        cull_header[cmd + 0u] = 2u * total;  // GL_LINES: two indices a segment
        cull_header[cmd + 1u] = 1u;
        cull_header[cmd + 2u] = 2u * base;
        cull_header[cmd + 3u] = 0u;
        cull_header[cmd + 4u] = 0u;
        cull_header[uint(CULL_H_SEGMENTS) + uint(u_cull_phase - 1)] = total;
    }
    barrier();
    if (t == 0u) {
        cull_header[uint(CULL_H_DRAWN) + uint(u_cull_phase - 1)] = s_drawn;
        if (u_cull_phase == 1) {
            cull_header[CULL_H_CHUNKS] = s_chunks;
            cull_header[CULL_H_OUTSIDE] = s_outside;
            // Until phase 2 runs (it does not without the depth test): nothing in it.
            cull_header[uint(CULL_H_CMD) + 5u] = 0u;
            cull_header[uint(CULL_H_CMD) + 6u] = 1u;
            cull_header[uint(CULL_H_CMD) + 7u] = 0u;
            cull_header[uint(CULL_H_CMD) + 8u] = 0u;
            cull_header[uint(CULL_H_CMD) + 9u] = 0u;
            cull_header[uint(CULL_H_SEGMENTS) + 1u] = 0u;
            cull_header[uint(CULL_H_DRAWN) + 1u] = 0u;
            cull_header[CULL_H_OCCLUDED] = 0u;
        } else {
            cull_header[CULL_H_OCCLUDED] = s_occluded;
        }
    }
}
