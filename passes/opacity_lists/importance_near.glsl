#version 450 core
// An importance hook for opacity_lists (importance=hook): what lies near a point of interest
// (the aneurysm, a stenosis) is important, falling off smoothly with the distance:
//   pathlet render variant4_opacity --set importance=hook \
//       --set opacity_lists.color_hook=importance_near.glsl --set opacity_lists.focus_center=[x,y,z]
#include "line_hooks.glsl"

uniform vec3 u_focus_center;   // @param [0, 0, 0] "the point of interest, in data coordinates"
uniform float u_focus_radius;  // @param 20 [0, 1e9] "distance (data units) at which the importance has fallen to 0"

vec4 line_color_hook(vec4 rgba, LinePoint p) {
    float d = distance(p.position, u_focus_center) / max(u_focus_radius, 1e-12);
    return vec4(rgba.rgb, 1.0 - smoothstep(0.0, 1.0, d));
}
