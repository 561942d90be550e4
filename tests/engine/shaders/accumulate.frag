#version 450 core
layout(location = 0) out vec4 o_color;
uniform sampler2D u_input0;  // the fullscreen pass's first input
void main() {
    o_color = texelFetch(u_input0, ivec2(gl_FragCoord.xy), 0) + vec4(10.0 / 255.0);
}
