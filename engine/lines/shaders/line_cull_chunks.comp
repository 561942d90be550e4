#version 450 core
// The line kit's GPU culling, per chunk (one invocation each): the chunk's piece of the time
// window, its strip after the level of detail (into its slot), the strip's box grown by the
// widest the line can be drawn, the frustum test, the box on screen for the depth test, and
// whether phase 1 draws it (visible last frame). See engine/lines/src/chunk_culler.hpp.
//
// The strips of a line's chunks together are the strip LineLod::select() gives the line's
// window range [f, l] (a, the kept points in (f, l), b; a and b the kept points around f and
// l): each chunk draws the segments that start at its kept points in [max(f, first),
// min(l, last)), the first piece also the one from a, and each ends at the next kept point,
// which may lie in a later chunk. So the chunks draw the same segments as the unculled draw,
// each once, and the chunk's box with the strip's points outside the chunk holds every segment
// the chunk draws.
#define CULL_USES_CHUNKS
#define CULL_USES_LOD
#define CULL_USES_POSITIONS
#define CULL_USES_LINES
#define CULL_USES_STATE
#define CULL_USES_SLOTS
#include "line_cull.glsl"

layout(local_size_x = CULL_GROUP) in;

uniform mat4 u_cull_view_proj;
uniform float u_cull_grow;      // world units every box grows by
uniform uint u_cull_chunks;     // chunks in the scene
uniform uint u_cull_points;     // points in the scene
uniform uint u_cull_skip_mask;  // LineLod's max_skip - 1 (a power of two; ~0u: none): point j is kept
                                // when (j - the line's first point) & mask is 0
uniform int u_cull_occlusion;   // 1: two phases (phase 1 = visible last frame); 0: everything in phase 1

bool kept(uint j, float eps, uint line_first) {
    return cull_keep[j] > eps || ((j - line_first) & u_cull_skip_mask) == 0u;
}

// Adds point j to the box when it lies outside the chunk (the chunk's box holds the rest; a
// point that is not finite has no segment drawn to it).
void grow_by(uint j, CullChunk ch, inout vec3 lo, inout vec3 hi) {
    if (j >= ch.first && j <= ch.last) return;
    vec3 p = cull_position(j);
    if (!any(isnan(p)) && !any(isinf(p))) lo = min(lo, p), hi = max(hi, p);
}

void main() {
    uint c = gl_GlobalInvocationID.x;
    if (c >= u_cull_chunks) return;
    bool was_visible = (cull_state[c].flags & kCullVisible) != 0u;
    CullState s;
    s.rect = vec4(-1.0, -1.0, 1.0, 1.0);
    s.zmin = 0.0;
    s.flags = 0u;
    s.count = 0u;
    s.offset = 0u;

    CullChunk ch = cull_chunk[c];
    uvec4 w = cull_line[ch.line];
    uint a = max(w.x, ch.first), b = min(w.y, ch.last);  // the window's piece of this chunk
    if (w.y < w.x || b <= a) {
        cull_state[c] = s;
        return;
    }
    float eps = uintBitsToFloat(w.z);
    // The strip's points into the chunk's slot: the kept point at or before the window's start
    // (first piece only), the kept points of [a, b), and the next kept point at or after b. A
    // line's ends are always kept, so the scans stop there at the latest. (Written without
    // branches: llvmpipe runs a work group's lanes in step, so a store every step is cheaper
    // than a divergent one; a store that is not kept is overwritten by the next.)
    uint base = c * uint(CULL_SLOT), n = 0u;
    vec3 lo = ch.lo, hi = ch.hi;  // the box of the strip's points: the chunk's, and its points outside the chunk
    if (a == w.x) {
        uint j = a;
        while (j > w.w && !kept(j, eps, w.w)) --j;
        if (j < a) {
            cull_slot[base] = j;
            n = 1u;
            grow_by(j, ch, lo, hi);
        }
    }
    for (uint j = a; j < b; ++j) {
        cull_slot[base + n] = j;
        n += kept(j, eps, w.w) ? 1u : 0u;
    }
    if (n == 0u) {  // no segment starts here: an earlier chunk's strip spans this one
        cull_state[c] = s;
        return;
    }
    uint j = b;
    while (j + 1u < u_cull_points && !kept(j, eps, w.w)) ++j;
    cull_slot[base + n] = j;
    ++n;
    grow_by(j, ch, lo, hi);
    // A chunk without a finite point has an empty box (lo > hi): never culled.
    bool finite = all(lessThanEqual(lo, hi));
    s.count = n - 1u;
    s.flags = kCullDrawn;

    if (finite) {
        lo -= vec3(u_cull_grow);
        hi += vec3(u_cull_grow);
        // Outside the frustum when all eight corners lie beyond one plane; on screen the
        // rectangle of the corners and their nearest depth, when every corner is in front of
        // the camera (window depth is monotonic in eye depth there, so a corner is the nearest).
        // A plane has every corner beyond it when the largest q - (-w) is < 0 or the smallest q - w > 0.
        vec3 above_neg = vec3(-1e38), below_pos = vec3(1e38);
        bool in_front = true;
        vec2 pmin = vec2(1e30), pmax = vec2(-1e30);
        float zmin = 1.0;
        for (int k = 0; k < 8; ++k) {
            vec4 q = u_cull_view_proj * vec4((k & 1) != 0 ? hi.x : lo.x, (k & 2) != 0 ? hi.y : lo.y, (k & 4) != 0 ? hi.z : lo.z, 1.0);
            above_neg = max(above_neg, q.xyz + q.w);
            below_pos = min(below_pos, q.xyz - q.w);
            in_front = in_front && q.w > 1e-6;
            vec3 ndc = q.xyz / q.w;
            pmin = min(pmin, ndc.xy);
            pmax = max(pmax, ndc.xy);
            zmin = min(zmin, 0.5 * ndc.z + 0.5);
        }
        if (any(lessThan(above_neg, vec3(0.0))) || any(greaterThan(below_pos, vec3(0.0)))) s.flags |= kCullOutside;
        if (in_front && zmin > 0.0) {
            s.rect = vec4(pmin, pmax);
            s.zmin = zmin;
            s.flags |= kCullTestable;
        }
    }
    if ((s.flags & kCullOutside) == 0u && (u_cull_occlusion == 0 || was_visible)) s.flags |= kCullPhase1;
    // Without the depth test, what is drawn counts as visible (the first frame with it draws that in phase 1).
    if (u_cull_occlusion == 0 && (s.flags & kCullPhase1) != 0u) s.flags |= kCullVisible;
    cull_state[c] = s;
}
