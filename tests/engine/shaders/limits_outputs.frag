#version 450 core
// Four colour outputs, three images and two storage blocks: nine output resources, one more
// than a minimal GL 4.5 driver's GL_MAX_COMBINED_SHADER_OUTPUT_RESOURCES (8).
layout(location = 0) out vec4 o0;
layout(location = 1) out vec4 o1;
layout(location = 2) out vec4 o2;
layout(location = 3) out vec4 o3;
layout(r32ui) uniform uimage2D u_a;
layout(r32ui) uniform uimage2D u_b;
layout(r32ui) uniform uimage2D u_c;
layout(std430, binding = 0) buffer S0 { uint s0; };
layout(std430, binding = 1) buffer S1 { uint s1; };
void main() {
    imageAtomicAdd(u_a, ivec2(0), 1u);
    imageAtomicAdd(u_b, ivec2(0), 1u);
    imageAtomicAdd(u_c, ivec2(0), 1u);
    atomicAdd(s0, 1u);
    atomicAdd(s1, 1u);
    o0 = o1 = o2 = o3 = vec4(1.0);
}
