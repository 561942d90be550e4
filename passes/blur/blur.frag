#version 450 core
// One direction of a separable Gaussian; weights normalised so flat areas stay flat.
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
uniform sampler2D u_src;  // the input; in the vertical pass, `tmp`
uniform int u_radius;
uniform float u_sigma;
uniform vec2 u_dir;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(u_src, 0);
    vec4 sum = vec4(0.0);
    float wsum = 0.0;
    for (int i = -u_radius; i <= u_radius; ++i) {
        ivec2 q = clamp(p + ivec2(u_dir) * i, ivec2(0), size - 1);
        float w = exp(-0.5 * float(i * i) / (u_sigma * u_sigma));
        sum += w * texelFetch(u_src, q, 0);
        wsum += w;
    }
    o_color = sum / wsum;
}
