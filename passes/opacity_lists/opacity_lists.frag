#version 450 core
// opacity_lists' fragment stage: every fragment of a pathlet quad at the reduced resolution
// becomes a node of its pixel's list (shaders/opacity_optimization.glsl): its segment (from the
// line and the arc length), its linear depth and its importance (the segment's, times the
// colour hook's opacity, and a faded-out fragment is no node; with OO_IMPORTANCE_HOOK the hook's
// opacity alone, and every fragment is a node).
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"
#include "opacity_optimization.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the pass's colour hook (color_hook)

layout(std430, binding = LISTS_BINDING) coherent buffer OoLists { uint oo_list[]; };  // the pin `lists`
// The pass's segmentation with the importance of segment s at [b[3] + S + s] (internal `source`).
layout(std430, binding = SOURCE_BINDING) readonly buffer OoSource { uint oo_src[]; };

void main() {
    LineFrag f = line_fragment();
    float a = clamp(line_color_hook(vec4(f.color, 1.0), f.point).a, 0.0, 1.0);
    uint s = oo_segment_of(oo_line(oo_src, f.point.line_id), f.point.arc);
#ifdef OO_IMPORTANCE_HOOK
    float g = a;  // the hook says how important; every fragment stays in the way
#else
    if (a < 0.5 / 255.0) discard;  // faded out (the end fade): neither shown nor in the way
    float g = a * uintBitsToFloat(oo_src[oo_per_segment(oo_src) + oo_segments(oo_src) + s]);
#endif
    uint i = atomicAdd(oo_list[OO_LIST_COUNT], 1u);
    if (i >= oo_list[OO_LIST_CAPACITY]) return;  // overflow: counted, the pass grows the buffer
    ivec2 px = ivec2(gl_FragCoord.xy);
    uint next = atomicExchange(oo_list[OO_LIST_HEADS + uint(px.y) * oo_list[OO_LIST_WIDTH] + uint(px.x)], i);
    uint n = oo_nodes_at(oo_list) + 4u * i;
    oo_list[n] = s;
    oo_list[n + 1u] = floatBitsToUint(f.depth01);
    oo_list[n + 2u] = floatBitsToUint(g);
    oo_list[n + 3u] = next;
}
