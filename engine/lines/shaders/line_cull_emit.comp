#version 450 core
// The line kit's GPU culling: every chunk drawn in this phase writes its strip's segments as
// GL_LINES index pairs where the scan placed them (one draw a phase: llvmpipe pays per draw).
#define CULL_USES_STATE
#define CULL_USES_SLOTS
#define CULL_USES_INDICES
#include "line_cull.glsl"

layout(local_size_x = CULL_GROUP) in;

uniform uint u_cull_chunks;
uniform int u_cull_phase;  // 1 or 2

void main() {
    uint c = gl_GlobalInvocationID.x;
    if (c >= u_cull_chunks) return;
    CullState s = cull_state[c];
    if ((s.flags & (u_cull_phase == 1 ? kCullPhase1 : kCullPhase2)) == 0u) return;
    uint slot = c * uint(CULL_SLOT), at = 2u * s.offset;
    uint prev = cull_slot[slot];
    for (uint k = 1u; k <= s.count; ++k) {
        uint next = cull_slot[slot + k];
        cull_index[at] = prev;
        cull_index[at + 1u] = next;
        at += 2u;
        prev = next;
    }
}
