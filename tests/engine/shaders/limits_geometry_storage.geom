#version 450 core
// A storage block in a geometry shader: legal where the driver allows it (llvmpipe, NVIDIA),
// refused on a minimal GL 4.5 driver (GL_MAX_GEOMETRY_SHADER_STORAGE_BLOCKS may be 0).
layout(points) in;
layout(points, max_vertices = 1) out;
layout(std430, binding = 0) readonly buffer Offsets { vec4 offset; };
void main() {
    gl_Position = gl_in[0].gl_Position + offset;
    EmitVertex();
}
