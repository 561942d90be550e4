#version 450 core
// The fixture's fragment stage: the nearest fragment's own AO, as any line pass can compute it.
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"
#include "line_volume_ao.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the kit's default hook, linked in

layout(location = 0) out float o_ao;

void main() {
    LineFrag f = line_fragment();
    o_ao = line_volume_ao_fragment(f);
    gl_FragDepth = line_window_depth(f.depth01);
}
