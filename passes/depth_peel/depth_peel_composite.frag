#version 450 core
// depth_peel's composite: the layer just peeled (every fragment at its depth, summed by the
// gather draw) goes under what is composited so far (front to back), and its depth becomes the
// pixel's last peeled. A pixel without a fragment in this layer keeps its colour (discard).
#include "oit_depth_group.glsl"

layout(rgba32f) uniform image2D u_accum;  // the pins, by declaration
layout(r32f) uniform image2D u_peeled;
uniform sampler2D u_peel_depth;
uniform sampler2D u_layer;       // the layer's fragments: (sum of w c.rgb, sum of w)
uniform vec3 u_background;

layout(location = 0) out vec4 o_color;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 layer = texelFetch(u_layer, p, 0);
    float d = texelFetch(u_peel_depth, p, 0).r;
    // Nothing peeled here: no fragment summed (every stored fragment has w > 0) and the depth
    // buffer still at its clear value. (A peeled depth below 1 advances even if nothing summed.)
    if (layer.a <= 0.0 && d >= 1.0) discard;
    vec4 acc = imageLoad(u_accum, p);
    oit_depth_group_composite(acc.rgb, acc.a, layer);
    imageStore(u_accum, p, acc);
    imageStore(u_peeled, p, vec4(d));
    o_color = vec4(acc.rgb + acc.a * u_background, 1.0);  // alpha 1 where a fragment landed
}
