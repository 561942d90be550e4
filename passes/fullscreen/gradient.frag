#version 450 core
// Test pattern: a colour gradient with a few sharp features (so blurs and goldens see edges).
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
uniform vec3 u_param;     // the pass parameters `param` and `strength`
uniform float u_strength;
uniform float u_time;
void main() {
    vec2 uv = v_uv;
    float checker = mod(floor(uv.x * 8.0) + floor(uv.y * 6.0), 2.0);
    float ring = step(abs(length(uv - 0.5) - 0.3), 0.02);
    vec3 c = vec3(uv, 0.5 + 0.5 * sin(u_time)) * (0.6 + 0.4 * checker);
    o_color = vec4(mix(c, u_param, ring * u_strength), 1.0);
}
