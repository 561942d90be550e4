#version 450 core
layout(location = 0) out vec4 o_color;
void main() {
    // the next line is missing a semicolon, on purpose
    o_color = vec4(1.0)
}
