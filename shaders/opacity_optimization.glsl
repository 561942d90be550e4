// Opacity optimization (Günther, Rössl, Theisel 2013; the decoupled per-pixel form of Günther,
// Theisel, Gross 2017) on Pathlet's lines: the layouts of the buffers its passes hand on, said
// once for opacity_lists, opacity_resolve, opacity_blend and the hooks (oo_opacity.glsl).
// Every buffer is a flat uint array (std430 `uint x[]`).
//
// Segments. Every line is cut by arc length into segments of about equal length; a segment is
// keyed to its line and its place along it, not to the time window, so a pathlet keeps its
// opacity as it moves. `segments` (opacity_lists' output) and `opacity` (opacity_blend's output,
// a kit pass's hook_buffer) share a header and the line table:
//   [0] lines L, [1] segments S, [2] generation (new with every segmentation), [3] the word of
//   the first per-segment entry (8 + 4 L), [4..6] work groups of OO_GROUP over max(S, 8 + 4 L)
//   (x, 1, 1: glDispatchComputeIndirect), [7] 0; then per line l at [8 + 4 l]: first segment,
//   count, segment length (float bits), 0; then per segment s at [b[3] + s]: `segments` its line,
//   `opacity` its opacity (float bits). opacity_lists keeps the importance of segment s at
//   [b[3] + S + s] in its own copy (float bits). opacity_lists.cpp writes this from C++.
//
// Lists (opacity_lists -> opacity_resolve), at the reduced resolution:
//   [0..2] work groups of opacity_resolve (x, y, 1: glDispatchComputeIndirect), [3] width,
//   [4] height, [5] node capacity, [6] node counter, [7] 0; then the heads (OO_END: empty), one
//   per pixel, rows bottom-up; then the nodes from oo_nodes_at(b), 4 words each: segment,
//   linear depth (float bits), importance (float bits), next node.
//
// Targets (opacity_resolve -> opacity_blend):
//   [0] segments that got a fragment this frame, [1..3] work groups of opacity_blend over them
//   (x, 1, 1), [4] longest list, [5] fragments beyond max_fragments, [6] pixels with such,
//   [7] 0; then per segment at [8 + s] the least opacity its fragments asked for (float bits,
//   OO_UNSEEN: no fragment); then at [8 + S + i] the i-th segment that got one.
#ifndef PATHLET_OPACITY_OPTIMIZATION_GLSL
#define PATHLET_OPACITY_OPTIMIZATION_GLSL

#define OO_END 0xFFFFFFFFu     // empty list / last node
#define OO_UNSEEN 0xFFFFFFFFu  // a segment without fragments (above every opacity's bits)

#define OO_HEADER_WORDS 8u
#define OO_SEGMENT_GROUPS 4u  // the header's work groups over the segments
#define oo_lines(b) (b[0])
#define oo_segments(b) (b[1])
#define oo_generation(b) (b[2])
#define oo_per_segment(b) (b[3])
// First segment, segment count, segment length (float bits) of line l.
#define oo_line(b, l) uvec3(b[OO_HEADER_WORDS + 4u * uint(l)], b[OO_HEADER_WORDS + 4u * uint(l) + 1u], \
                            b[OO_HEADER_WORDS + 4u * uint(l) + 2u])

#define OO_LIST_GROUPS 0u
#define OO_LIST_WIDTH 3u
#define OO_LIST_HEIGHT 4u
#define OO_LIST_CAPACITY 5u
#define OO_LIST_COUNT 6u
#define OO_LIST_HEADS 8u
#define oo_nodes_at(b) ((OO_LIST_HEADS + b[OO_LIST_WIDTH] * b[OO_LIST_HEIGHT] + 3u) & ~3u)

#define OO_TARGET_COUNT 0u
#define OO_TARGET_GROUPS 1u
#define OO_TARGET_PEAK 4u
#define OO_TARGET_BEYOND 5u
#define OO_TARGET_TRUNCATED 6u
#define OO_TARGET_ALPHA 8u
#define OO_GROUP 64u  // opacity_blend's work group size

// The segment at arc length `arc` of a line (oo_line).
uint oo_segment_of(uvec3 line, float arc) {
    float len = uintBitsToFloat(line.z);
    float k = len > 0.0 ? max(arc, 0.0) / len : 0.0;
    return line.x + min(uint(min(k, 4.0e9)), line.y - 1u);
}

// The two segments whose centres enclose arc length `arc` and the weight of the second: a value
// per segment read this way is linear in arc length between centres (what the reference
// implementations interpolate per vertex), constant from the last centre to the line's end.
struct OoPair {
    uint a, b;
    float t;
};
OoPair oo_pair_of(uvec3 line, float arc) {
    float len = uintBitsToFloat(line.z);
    float u = len > 0.0 ? clamp(arc / len - 0.5, 0.0, float(line.y - 1u)) : 0.0;
    float k = floor(u);
    OoPair p;
    p.a = line.x + uint(k);
    p.b = min(p.a + 1u, line.x + line.y - 1u);
    p.t = u - k;
    return p;
}

#endif
