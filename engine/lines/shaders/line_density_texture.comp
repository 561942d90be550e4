#version 450 core
// The line-density cells (fixed point in the LineDensity storage block) into the filterable 3D
// texture line_density_at() samples, as normalised uint (value / (2^32 - 1)). Done here and not
// by a pixel-buffer upload: a driver may convert such an upload on the CPU, after waiting for
// the splat (lines::VolumeAo::bind).
#include "line_density.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(r32f) writeonly uniform image3D u_density_target;

void main() {
    const ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, density_dims.xyz))) return;
    imageStore(u_density_target, c, vec4(float(density_cells[line_density_index(c)]) / 4294967295.0));
}
