// The line kit's GPU culling (engine/lines/src/chunk_culler.hpp): what its compute stages
// share. The binding points, the chunk length, the header's layout and the vertex layout come
// from the C++ side as defines (ChunkCuller::defines()); a stage defines CULL_USES_<BUFFER>
// for each buffer it reads or writes before including this.
#ifndef PATHLET_LINE_CULL_GLSL
#define PATHLET_LINE_CULL_GLSL

// Per chunk, what the chunk stage found this frame (flags below), read by the later stages.
struct CullState {
    vec4 rect;   // the grown box on screen: NDC x0, y0, x1, y1
    float zmin;  // its nearest window depth (0: never hidden)
    uint flags;
    uint count;   // segments of the chunk's strip (its points in the slot, minus one)
    uint offset;  // where its segments start in the index buffer (in segments), by the scan
};
const uint kCullDrawn = 1u;       // its strip has a segment in the window
const uint kCullOutside = 2u;     // ... but the box lies outside the view frustum
const uint kCullTestable = 4u;    // the box lies wholly in front of the camera (a depth test can hide it)
const uint kCullPhase1 = 8u;      // drawn in phase 1 (visible last frame)
const uint kCullPhase2 = 16u;     // drawn in phase 2 (not hidden by phase 1's depth)
const uint kCullOccluded = 32u;   // hidden behind phase 1's depth: not drawn
const uint kCullVisible = 64u;    // next frame's phase 1

#ifdef CULL_USES_CHUNKS
struct CullChunk {  // GpuScene::chunk_buffer()
    vec3 lo;
    uint first;
    vec3 hi;
    uint last;
    uint line;
    uint pad0, pad1, pad2;
};
layout(std430, binding = CULL_CHUNKS_BINDING) readonly buffer CullChunks { CullChunk cull_chunk[]; };
#endif
#ifdef CULL_USES_LOD
// Per point, the level of detail's tolerance: kept when it exceeds the line's tolerance.
layout(std430, binding = CULL_LOD_BINDING) readonly buffer CullLod { float cull_keep[]; };
#endif
#ifdef CULL_USES_POSITIONS
// Per point its position (GpuScene::points_buffer(), decoded by scene_points.glsl).
#include "scene_points.glsl"
layout(std430, binding = CULL_POSITIONS_BINDING) readonly buffer CullPositions { uint cull_point_word[]; };
vec3 cull_position(uint i) { return SCENE_POINT_FROM_WORDS(cull_point_word, i); }
#endif
#ifdef CULL_USES_LINES
// Per line, this frame: the window's first and last point (last < first: none), the level of
// detail's tolerance (float bits; < 0 keeps every point) and the line's first point.
layout(std430, binding = CULL_LINES_BINDING) readonly buffer CullLines { uvec4 cull_line[]; };
#endif
#ifdef CULL_USES_STATE
layout(std430, binding = CULL_STATE_BINDING) buffer CullStates { CullState cull_state[]; };
#endif
#ifdef CULL_USES_SLOTS
// CULL_SLOT point indices per chunk: its strip after the level of detail.
layout(std430, binding = CULL_SLOTS_BINDING) buffer CullSlots { uint cull_slot[]; };
#endif
#ifdef CULL_USES_INDICES
// The draw's GL_LINES index pairs, phase 1's then phase 2's.
layout(std430, binding = CULL_INDICES_BINDING) writeonly buffer CullIndices { uint cull_index[]; };
#endif
#ifdef CULL_USES_HEADER
// The two phases' draw commands and the frame's counts (offsets CULL_H_*, in uints).
layout(std430, binding = CULL_HEADER_BINDING) buffer CullHeader { uint cull_header[]; };
#endif

#endif
