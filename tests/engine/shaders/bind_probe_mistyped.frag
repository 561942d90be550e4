#version 450 core
// A uniform named after a parameter with another type: binding must refuse it by name.
layout(location = 0) out vec4 o_color;
uniform vec2 u_gain;
void main() { o_color = vec4(u_gain, 0.0, 1.0); }
