#version 450 core
// opacity_blend: what opacity_resolve found per segment, smoothed along each line and blended
// in time, published for the colour hooks. One program, three phases (u_phase):
//   0 smoothing step over the segments that got fragments: a Jacobi step of the Laplacian along
//     the line, v += rate (v_left / 2 + v_right / 2 - v), a neighbour without fragments this
//     frame (or past the line's end) counting as the segment itself (as LineVis does);
//   1 the temporal blend over the same segments: v = mix(state, smoothed, u_blend) with u_blend
//     = 1 - 2^(-dt / half_life) (frame-rate independent), or the smoothed value for a segment
//     without a state of this segmentation;
//   2 publish over every segment: `opacity` = the header and line table of `segments`, then each
//     segment's state, or a neighbour's for a segment never seen, or 1.
layout(local_size_x = 64) in;

#include "opacity_optimization.glsl"

// The pins and the pass's own buffers, on their bindings by declaration.
layout(std430, binding = SEGMENTS_BINDING) readonly buffer OoSegments { uint oo_seg[]; };
layout(std430, binding = TARGETS_BINDING) readonly buffer OoTargets { uint oo_target[]; };
layout(std430, binding = OPACITY_BINDING) writeonly buffer OoOpacity { uint oo_out[]; };
layout(std430, binding = STATE_BINDING) buffer OoState { uvec2 oo_state[]; };  // opacity bits, generation
layout(std430, binding = SMOOTH_A_BINDING) buffer OoSmoothA { float oo_a[]; };
layout(std430, binding = SMOOTH_B_BINDING) buffer OoSmoothB { float oo_b[]; };

uniform int u_phase;
uniform int u_from;  // where this step's values are: 0 the targets, 1 smooth_a, 2 smooth_b
uniform float u_smoothing_rate;
uniform float u_blend;  // weight of this frame's value

bool seen_now(uint s) { return oo_target[OO_TARGET_ALPHA + s] != OO_UNSEEN; }
float value(uint s) { return u_from == 0 ? uintBitsToFloat(oo_target[OO_TARGET_ALPHA + s]) : (u_from == 1 ? oo_a[s] : oo_b[s]); }
void store(uint s, float v) {  // into the other smoothing buffer
    if (u_from == 1) oo_b[s] = v;
    else oo_a[s] = v;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint segments = oo_segments(oo_seg), generation = oo_generation(oo_seg);
    if (u_phase == 2) {
        uint per_segment = oo_per_segment(oo_seg);
        if (i < per_segment) oo_out[i] = oo_seg[i];  // header and line table
        if (i >= segments) return;
        uvec3 line = oo_line(oo_seg, oo_seg[per_segment + i]);
        uint left = max(i, line.x + 1u) - 1u, right = min(i + 1u, line.x + line.y - 1u);
        float a = 1.0;
        if (oo_state[i].y == generation) a = uintBitsToFloat(oo_state[i].x);
        else if (oo_state[left].y == generation) a = uintBitsToFloat(oo_state[left].x);
        else if (oo_state[right].y == generation) a = uintBitsToFloat(oo_state[right].x);
        oo_out[per_segment + i] = floatBitsToUint(a);
        return;
    }
    if (i >= oo_target[OO_TARGET_COUNT]) return;
    uint s = oo_target[OO_TARGET_ALPHA + segments + i];
    float v = value(s);
    if (u_phase == 0) {
        uvec3 line = oo_line(oo_seg, oo_seg[oo_per_segment(oo_seg) + s]);
        uint left = max(s, line.x + 1u) - 1u, right = min(s + 1u, line.x + line.y - 1u);
        float vl = seen_now(left) ? value(left) : v, vr = seen_now(right) ? value(right) : v;
        store(s, v + u_smoothing_rate * (0.5 * (vl + vr) - v));
        return;
    }
    uvec2 st = oo_state[s];
    float a = st.y == generation ? mix(uintBitsToFloat(st.x), v, u_blend) : v;
    oo_state[s] = uvec2(floatBitsToUint(clamp(a, 0.0, 1.0)), generation);
}
