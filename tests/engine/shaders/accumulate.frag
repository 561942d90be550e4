#version 450 core
layout(location = 0) out vec4 o_color;
layout(binding = 0) uniform sampler2D u_prev;
void main() {
    o_color = texelFetch(u_prev, ivec2(gl_FragCoord.xy), 0) + vec4(10.0 / 255.0);
}
