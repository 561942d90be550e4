#version 450 core
// depth_peel's line stage, one program for its three draws (u_phase), so the depth of a
// fragment is computed by the same code in each and compares equal bit for bit:
//   0 coverage: where visible fragments are, the quad's depth (depth test ALWAYS): fill_list's
//               coverage bit for bit, so the wall shows where it shows in variant2_exact
//   1 peel:     the nearest depth behind the last layer peeled, among the fragments of pixels
//               that still let light through: into the depth buffer (test LEQUAL against 1.0,
//               so fragments clamped to the far plane are peeled too)
//   2 gather:   every fragment at exactly that depth adds its share of the layer
//               (oit_depth_group.glsl: one depth, one layer, as resolve_exact composites it)
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"
#include "oit_fragment.glsl"
#include "oit_depth_group.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the pass's colour hook (color_hook)

layout(rgba32f) uniform readonly image2D u_accum;   // the pins, by declaration: colour so far, transmittance
layout(r32f) uniform readonly image2D u_peeled;     // the depth of the last layer peeled (-1: none)
uniform sampler2D u_peel_depth;                     // this layer's depth (phase 2)
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
    if (f.depth01 <= imageLoad(u_peeled, p).r) discard;          // in a layer peeled already
    if (u_phase == 1) {
        gl_FragDepth = f.depth01;
        o_color = c;
        return;
    }
    if (f.depth01 != texelFetch(u_peel_depth, p, 0).r) discard;  // not this layer
    o_color = oit_depth_group_term(oit_list_stored(c));           // summed by additive blending
}
