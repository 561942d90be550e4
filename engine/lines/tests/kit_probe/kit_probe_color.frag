#version 450 core
#include "line_hooks.glsl"
uniform int u_mode;
uniform float u_scale;
// "bound": a colour from the pass's own storage buffer plus one from its own texture, bound
// before the kit draws (the kit's culling uses the same binding point and unit in between).
layout(std430, binding = PROBE_BUFFER_BINDING) readonly buffer ProbeColor { vec4 probe_color; };
uniform sampler2D u_probe_texture;
vec4 line_color_hook(vec4 rgba, LinePoint p) {
    if (u_mode == 0) return vec4(p.age, 0.0, 0.0, 1.0);
    if (u_mode == 1) return vec4(p.arc_from_head / u_scale, p.arc_from_tail / u_scale, 0.0, 1.0);
    if (u_mode == 5) return vec4(probe_color.rgb + texelFetch(u_probe_texture, ivec2(0), 0).rgb, 1.0);
    return rgba;
}
