#version 450 core
// An importance hook for opacity_lists (importance=hook): the head of a pathlet (its most recent
// part) is important, its tail not, times the speed on the colour map's range:
//   pathlet render variant4_opacity --set importance=hook --set opacity_lists.color_hook=importance_recent.glsl
#include "line_hooks.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p) {
    float s = clamp((p.speed - u_speed_range.x) / max(u_speed_range.y - u_speed_range.x, 1e-12), 0.0, 1.0);
    return vec4(rgba.rgb, (1.0 - p.age) * s);
}
