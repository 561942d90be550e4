#version 450 core
// mlab_blend's resolve: the front bucket, then the nodes front to back, over the background.
layout(std430, binding = NODES_BINDING) readonly buffer MlabNodes { uvec2 mlab_slot[]; };
uniform int u_width;
uniform vec3 u_background;

layout(location = 0) out vec4 o_color;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    uint base = uint(p.y * u_width + p.x) * uint(MLAB_LAYERS + 1);
    bool covered = mlab_slot[base] != uvec2(0u);
    vec4 sum = unpackUnorm4x8(mlab_slot[base].x);  // premultiplied, alpha = 1 - transmittance
    for (int k = 1; k <= MLAB_LAYERS; ++k) {
        uvec2 s = mlab_slot[base + uint(k)];
        if (s == uvec2(0u)) break;
        covered = true;
        sum += (1.0 - sum.a) * unpackUnorm4x8(s.x);
    }
    o_color = covered ? vec4(sum.rgb + (1.0 - sum.a) * u_background, 1.0) : vec4(u_background, 0.0);
}
