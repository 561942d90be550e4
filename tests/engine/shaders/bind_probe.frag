#version 450 core
// bind_probe's shader: every uniform is named after a parameter or pin of the pass, and
// nothing in C++ sets one; pixel x of the first row reports group x.
layout(location = 0) out vec4 o_color;
uniform int u_count;
uniform float u_gain;
uniform bool u_flag;
uniform int u_mode;
uniform vec3 u_tint;
uniform float u_radius_px;
uniform sampler2D u_src;
uniform sampler2D u_scratch;
void main() {
    int x = int(gl_FragCoord.x);
    if (x == 0) o_color = vec4(float(u_count), u_gain, u_flag ? 1.0 : 0.0, float(u_mode));
    else if (x == 1) o_color = vec4(u_tint, u_radius_px);
    else if (x == 2) o_color = texelFetch(u_src, ivec2(0), 0);
    else o_color = texelFetch(u_scratch, ivec2(0), 0);
}
