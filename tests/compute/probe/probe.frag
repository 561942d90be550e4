#version 450 core
// The SDK's compute probe (test_compute_ports.cpp): writes u_color's colour, and the pixel's own
// coordinates in blue/alpha, to every pixel it shades, as a fragment or a compute shader.
#include "fullscreen_pass.glsl"

#ifdef FULLSCREEN_COMPUTE
layout(rgba8) writeonly uniform image2D u_out;
void write_out(ivec2 p, vec4 c) { imageStore(u_out, p, c); }
#else
layout(location = 0) out vec4 o_out;
void write_out(ivec2 p, vec4 c) { o_out = c; }
#endif
uniform vec3 u_color;  // the parameter

void main() {
    ivec2 p;
    if (!fullscreen_pixel(p)) return;
    write_out(p, vec4(u_color.rg, float(p.x) / 255.0, float(p.y) / 255.0));
}
