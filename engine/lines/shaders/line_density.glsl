// The line-density volume (built by the line_density pass, read by volume_ao and by any line
// pass through line_volume_ao.glsl): a grid of cubic voxels over the lines' bounds holding, per
// voxel, the length of pathlet (visible in the time window) near it, splatted with trilinear
// weights. Stored as fixed point in a shader storage buffer so the splat's integer atomics are
// exact and the sum does not depend on the order the segments arrive in (deterministic frames).
// Define LINE_DENSITY_WRITE before including this to get a writable buffer (the splat);
// readers get line_density_at() from a 3D texture copy of the cells.
#ifndef PATHLET_LINE_DENSITY_GLSL
#define PATHLET_LINE_DENSITY_GLSL

// LINE_DENSITY_BINDING and LINE_DENSITY_SCALE (fixed-point counts per voxel length) come from
// pathlet::lines::density_defines(), where they are declared once.
#if !defined(LINE_DENSITY_BINDING) || !defined(LINE_DENSITY_SCALE)
#error "compile line_density.glsl with pathlet::lines::density_defines() (VolumeAo::defines includes them)"
#endif

layout(std430, binding = LINE_DENSITY_BINDING)
#ifndef LINE_DENSITY_WRITE
readonly
#endif
buffer LineDensity {
    ivec4 density_dims;    // voxels along x, y, z; w: 1 once built
    vec4 density_origin;   // xyz: world position of voxel (0,0,0)'s corner; w: voxel size h
    vec4 density_info;     // x: window start, y: window end (seconds), zw: unused
    uint density_cells[];  // x fastest, fixed point (LINE_DENSITY_SCALE per voxel length)
};

// Grid coordinates of a world point: voxel (i, j, k)'s centre is at (i, j, k).
vec3 line_density_grid(vec3 world) {
    return (world - density_origin.xyz) / density_origin.w - 0.5;
}

uint line_density_index(ivec3 c) {
    return uint(c.x + density_dims.x * (c.y + density_dims.y * c.z));
}

#ifndef LINE_DENSITY_WRITE
// The cells as a filterable 3D texture: lines::VolumeAo copies them into it every frame as
// normalised uint (one hardware trilinear fetch costs llvmpipe a third of eight buffer loads).
uniform sampler3D u_density_cells;

// The texture's value times this is pathlet length per voxel, in voxel lengths.
const float kLineDensityUnit = 4294967295.0 / LINE_DENSITY_SCALE;

// Texture coordinates of grid point g, and the texture's value there in units of
// kLineDensityUnit (a ray marcher steps in these coordinates and folds the unit into its rates).
vec3 line_density_texcoord(vec3 g) {
    return (g + 0.5) / vec3(density_dims.xyz);
}
float line_density_raw(vec3 texcoord) {
    return textureLod(u_density_cells, texcoord, 0.0).r;
}

// Pathlet length per voxel near grid point g (trilinear), in voxel lengths; beyond the grid the
// border voxels, which are empty (a margin of two voxels).
float line_density_at(vec3 g) {
    return line_density_raw(line_density_texcoord(g)) * kLineDensityUnit;
}
#endif

#endif
