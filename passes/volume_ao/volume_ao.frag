#version 450 core
// volume_ao per pixel: the kit's estimate from the density volume (line_volume_ao.glsl) for
// the G-buffer's point and normal and the line's axis from the tangent target; optionally
// times a weighted screen-space term (the hybrid).
#include "line_volume_ao.glsl"

uniform sampler2D u_normal_depth;  // the pins and the parameter, by declaration
uniform sampler2D u_tangent;
#ifdef SCREEN_AO
uniform sampler2D u_screen_ao;
uniform float u_screen_weight;
#endif

layout(location = 0) out float o_ao;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 nd = texelFetch(u_normal_depth, px, 0);
    if (dot(nd.xyz, nd.xyz) < 0.01) {  // background
        o_ao = 1.0;
        return;
    }
    vec4 tw = texelFetch(u_tangent, px, 0);
    o_ao = line_volume_ao_gbuffer(gl_FragCoord.xy, nd.w, nd.xyz, tw.xyz, tw.w);
#ifdef SCREEN_AO
    o_ao *= mix(1.0, texelFetch(u_screen_ao, px, 0).r, u_screen_weight);
#endif
}
