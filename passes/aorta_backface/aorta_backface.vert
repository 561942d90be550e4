#version 450 core
// The vessel wall in view space (GpuScene::mesh_vao: location 0 position, 1 normal).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_view;
uniform mat4 u_proj;
out vec3 v_normal;
out vec3 v_pos;
void main() {
    vec4 p = u_view * vec4(a_position, 1.0);
    v_pos = p.xyz;
    v_normal = mat3(u_view) * a_normal;
    gl_Position = u_proj * p;
}
