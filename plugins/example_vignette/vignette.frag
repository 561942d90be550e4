#version 450 core
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
uniform sampler2D u_src;  // the pin `src`
uniform float u_strength;
uniform float u_radius;
void main() {
    vec4 c = texture(u_src, v_uv);
    float d = length(v_uv - 0.5) * 1.41421356;
    float k = 1.0 - u_strength * smoothstep(u_radius * 0.5, u_radius * 1.2, d);
    o_color = vec4(c.rgb * k, c.a);
}
