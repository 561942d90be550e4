#version 450 core
// depth_peel's composite: the layer just peeled (its depth, the winning line id and colour)
// goes under what is composited so far (front to back), and becomes the last peeled fragment.
// A pixel without a fragment in this layer keeps its colour (discard).
layout(rgba32f) uniform image2D u_accum;  // the pins, by declaration
layout(rg32ui) uniform uimage2D u_key;
uniform sampler2D u_peel_depth;
uniform sampler2D u_layer_id;    // id / 2^24 of the fragment that won
uniform sampler2D u_layer;       // its colour (rgba8, as the lists store it)
uniform vec3 u_background;

layout(location = 0) out vec4 o_color;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float d = texelFetch(u_peel_depth, p, 0).r;
    if (d >= 1.0) discard;  // nothing peeled here
    vec4 c = texelFetch(u_layer, p, 0);
    uint id = uint(round(texelFetch(u_layer_id, p, 0).r * 16777216.0));
    vec4 acc = imageLoad(u_accum, p);
    acc.rgb += acc.a * c.a * c.rgb;
    acc.a *= 1.0 - c.a;
    imageStore(u_accum, p, acc);
    imageStore(u_key, p, uvec4(floatBitsToUint(d), id, 0u, 0u));
    o_color = vec4(acc.rgb + acc.a * u_background, 1.0);  // alpha 1 where a fragment landed
}
