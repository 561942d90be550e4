#version 450 core
// image_hog's first program: five of its ten image pins.
layout(local_size_x = 1) in;
layout(r32ui) uniform writeonly uimage2D u_i0;
layout(r32ui) uniform writeonly uimage2D u_i1;
layout(r32ui) uniform writeonly uimage2D u_i2;
layout(r32ui) uniform writeonly uimage2D u_i3;
layout(r32ui) uniform writeonly uimage2D u_i4;
void main() {
    imageStore(u_i0, ivec2(0), uvec4(1u));
    imageStore(u_i1, ivec2(0), uvec4(2u));
    imageStore(u_i2, ivec2(0), uvec4(3u));
    imageStore(u_i3, ivec2(0), uvec4(4u));
    imageStore(u_i4, ivec2(0), uvec4(5u));
}
