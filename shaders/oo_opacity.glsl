// The opacity that opacity optimization found (opacity_blend's `opacity`), as a colour or width
// hook reads it: the pass's `hook_buffer` must be connected to that buffer (the line kit refuses
// a hook that reads the block without it). Included by optimized_fade.glsl (fill_list's and
// fade_core's hook in variant 4); include it in a hook of your own to combine it with other rules.
#ifndef PATHLET_OO_OPACITY_GLSL
#define PATHLET_OO_OPACITY_GLSL

#include "line_hook_buffer.glsl"
#include "line_hooks.glsl"
#include "opacity_optimization.glsl"

// Linear in arc length between the centres of the point's segments; 1 on a line the buffer
// does not know (another data set's ids).
float optimized_opacity(LinePoint p) {
    if (uint(p.line_id) >= oo_lines(hook_buffer)) return 1.0;
    OoPair s = oo_pair_of(oo_line(hook_buffer, p.line_id), p.arc);
    uint at = oo_per_segment(hook_buffer);
    return mix(uintBitsToFloat(hook_buffer[at + s.a]), uintBitsToFloat(hook_buffer[at + s.b]), s.t);
}

#endif
