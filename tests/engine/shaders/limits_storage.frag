#version 450 core
// storage_probe: its internal buffer on the binding point the engine gave it, and twenty
// sampler units in use (internal textures, all cleared to zero) so the next pass can check that
// the reset between passes unbinds all of them.
layout(std430, binding = DATA_BINDING) readonly buffer Data { vec4 data; };
uniform sampler2D u_t0;
uniform sampler2D u_t1;
uniform sampler2D u_t2;
uniform sampler2D u_t3;
uniform sampler2D u_t4;
uniform sampler2D u_t5;
uniform sampler2D u_t6;
uniform sampler2D u_t7;
uniform sampler2D u_t8;
uniform sampler2D u_t9;
uniform sampler2D u_t10;
uniform sampler2D u_t11;
uniform sampler2D u_t12;
uniform sampler2D u_t13;
uniform sampler2D u_t14;
uniform sampler2D u_t15;
uniform sampler2D u_t16;
uniform sampler2D u_t17;
uniform sampler2D u_t18;
uniform sampler2D u_t19;
out vec4 frag;
void main() {
    float zero = texelFetch(u_t0, ivec2(0), 0).a + texelFetch(u_t1, ivec2(0), 0).a + texelFetch(u_t2, ivec2(0), 0).a + texelFetch(u_t3, ivec2(0), 0).a + texelFetch(u_t4, ivec2(0), 0).a + texelFetch(u_t5, ivec2(0), 0).a + texelFetch(u_t6, ivec2(0), 0).a + texelFetch(u_t7, ivec2(0), 0).a + texelFetch(u_t8, ivec2(0), 0).a + texelFetch(u_t9, ivec2(0), 0).a + texelFetch(u_t10, ivec2(0), 0).a + texelFetch(u_t11, ivec2(0), 0).a + texelFetch(u_t12, ivec2(0), 0).a + texelFetch(u_t13, ivec2(0), 0).a + texelFetch(u_t14, ivec2(0), 0).a + texelFetch(u_t15, ivec2(0), 0).a + texelFetch(u_t16, ivec2(0), 0).a + texelFetch(u_t17, ivec2(0), 0).a + texelFetch(u_t18, ivec2(0), 0).a + texelFetch(u_t19, ivec2(0), 0).a;
    frag = data + vec4(zero * 1e-30);  // the taps stay live, the value stays exact
}
