#version 450 core
// depth_peel's line stage, one program for its three draws (u_phase), so the depth of a
// fragment is computed by the same code in each and compares equal bit for bit:
//   0 coverage: where visible fragments are, the quad's depth (depth test ALWAYS): fill_list's
//               coverage bit for bit, so the wall shows where it shows in variant2_exact
//   1 peel:     the nearest fragment after the last peeled one, by (depth, line id), whose pixel
//               still lets light through: its linear depth into the depth buffer (test LESS)
//   2 select:   among the fragments at the peeled depth, the smallest line id wins the depth
//               test (id / 2^24 as depth) and writes its colour
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"
#include "oit_fragment.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the pass's colour hook (color_hook)

layout(rgba32f) uniform readonly image2D u_accum;  // the pins, by declaration: colour so far, transmittance
layout(rg32ui) uniform readonly uimage2D u_key;    // the last peeled fragment: depth bits, line id
uniform sampler2D u_peel_depth;                    // this layer's depth (phase 2)
uniform int u_phase;
uniform float u_min_transmittance;

layout(location = 0) out vec4 o_color;

void main() {
    LineFrag f = line_fragment();
    vec4 c = oit_fragment_rgba(f, line_color_hook(vec4(f.color, 1.0), f.point));
    if (!oit_fragment_visible(c.a)) discard;
    if (u_phase == 0) {
        gl_FragDepth = gl_FragCoord.z;  // what fill_list's coverage keeps (it writes no depth)
        o_color = c;
        return;
    }
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (imageLoad(u_accum, p).a < u_min_transmittance) discard;  // this pixel is done
    uvec2 last = imageLoad(u_key, p).xy;
    float last_depth = uintBitsToFloat(last.x);
    uint id = uint(f.point.line_id);
    if (f.depth01 < last_depth || (f.depth01 == last_depth && id <= last.y)) discard;  // peeled already
    if (u_phase == 1) {
        gl_FragDepth = f.depth01;
        o_color = c;
        return;
    }
    if (f.depth01 != texelFetch(u_peel_depth, p, 0).r) discard;  // not this layer
    gl_FragDepth = float(id) * (1.0 / 16777216.0);  // exact for ids below 2^24 (checked in setup)
    o_color = c;
}
