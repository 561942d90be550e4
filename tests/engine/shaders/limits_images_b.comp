#version 450 core
// image_hog's second program: the other five image pins.
layout(local_size_x = 1) in;
layout(r32ui) uniform writeonly uimage2D u_i5;
layout(r32ui) uniform writeonly uimage2D u_i6;
layout(r32ui) uniform writeonly uimage2D u_i7;
layout(r32ui) uniform writeonly uimage2D u_i8;
layout(r32ui) uniform writeonly uimage2D u_i9;
void main() {
    imageStore(u_i5, ivec2(0), uvec4(6u));
    imageStore(u_i6, ivec2(0), uvec4(7u));
    imageStore(u_i7, ivec2(0), uvec4(8u));
    imageStore(u_i8, ivec2(0), uvec4(9u));
    imageStore(u_i9, ivec2(0), uvec4(10u));
}
