// Per-pixel linked lists for order-independent transparency (Yang et al. 2010), shared by
// clear_list, fill_list, resolve_list and resolve_exact so their layout cannot disagree.
//   heads: r32ui image, one list head per pixel, OIT_END when empty (clear_list)
//   nodes: a buffer of uvec4 (16 bytes) read through a buffer texture:
//          x colour (packUnorm4x8, straight alpha), y linear depth (float bits),
//          z next node (OIT_END ends the list), w line id (ties: deterministic order)
//   counter: std430 buffer, the number of nodes appended this frame (may exceed capacity:
//          then the frame overflowed and fill_list re-renders it with a larger buffer); a
//          buffer pin, so its binding point is the engine's (COUNTER_BINDING for pin "counter")
#ifndef PATHLET_OIT_LIST_GLSL
#define PATHLET_OIT_LIST_GLSL

// OIT_END comes from C++ (pathlet::oit::defines(), pathlet/oit.hpp).
#if !defined(OIT_END)
#error "oit_list.glsl: make the program with pathlet::oit::defines()"
#endif

uvec4 oit_pack(vec4 rgba, float depth01, uint next, int line_id) {
    return uvec4(packUnorm4x8(clamp(rgba, 0.0, 1.0)), floatBitsToUint(depth01), next, uint(line_id));
}
vec4 oit_color(uvec4 n) { return unpackUnorm4x8(n.x); }
float oit_depth(uvec4 n) { return uintBitsToFloat(n.y); }
uint oit_next(uvec4 n) { return n.z; }
uint oit_line(uvec4 n) { return n.w; }

// The order the list resolves sort in: depth, then line id, then colour. Identical keys are
// identical fragments, so the picture never depends on the order the rasteriser appended them.
// (resolve_exact composites the fragments at one depth as one layer, as depth peeling does:
// oit_depth_group.glsl.)
bool oit_nearer(float d, uint id, uint c, float d2, uint id2, uint c2) {
    return d < d2 || (d == d2 && (id < id2 || (id == id2 && c < c2)));
}

#endif
