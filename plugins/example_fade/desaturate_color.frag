#version 450 core
// The fade itself: from age u_start to the tail, the speed colour slides to a light grey (and,
// with u_dither, out: the kit turns alpha into screen-door coverage on opaque targets).
#include "line_hooks.glsl"

uniform float u_start;
uniform vec3 u_grey;
uniform int u_dither;

vec4 line_color_hook(vec4 rgba, LinePoint p) {
    float k = smoothstep(u_start, 1.0, p.age);
    float luma = dot(rgba.rgb, vec3(0.2126, 0.7152, 0.0722));
    vec3 faded = mix(vec3(luma), u_grey, 0.6);
    return vec4(mix(rgba.rgb, faded, k), u_dither != 0 ? 1.0 - k : 1.0);
}
