#version 450 core
// One triangle that covers the viewport; v_uv is 0..1 over the screen. u_fullscreen_z = 1
// puts it on the far plane, so a GREATER depth test against a G-buffer depth keeps only
// pixels covered by geometry (PassContext::draw_fullscreen_on_geometry).
out vec2 v_uv;
uniform float u_fullscreen_z;
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    v_uv = p;
    gl_Position = vec4(p * 2.0 - 1.0, u_fullscreen_z, 1.0);
}
