#version 450 core
// mlab_bucket's fragment stage: the fragment's depth where it is opaque enough for either bucket
// boundary, else 1 (MIN blending keeps the nearest).
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"
#include "oit_blend.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the pass's colour hook (color_hook)

uniform float u_lower_opacity;
uniform float u_upper_opacity;

layout(location = 0) out vec4 o_bucket;

void main() {
    LineFrag f = line_fragment();
    vec4 c = oit_fragment_rgba(f, line_color_hook(vec4(f.color, 1.0), f.point));
    if (!oit_fragment_visible(c.a)) discard;
    o_bucket = vec4(c.a > u_lower_opacity ? f.depth01 : 1.0, c.a >= u_upper_opacity ? f.depth01 : 1.0, 1.0, 1.0);
}
