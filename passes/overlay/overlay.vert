#version 450 core
// A screen rectangle given in pixels from the top-left corner (u_rect = x0, y0, x1, y1).
uniform vec4 u_rect;
uniform vec2 u_size;  // target size in pixels
out vec2 v_uv;        // 0..1 across the rectangle, v = 0 at its top
void main() {
    vec2 c = vec2(gl_VertexID & 1, (gl_VertexID >> 1) & 1);
    v_uv = c;
    vec2 px = mix(u_rect.xy, u_rect.zw, c);
    gl_Position = vec4(px.x / u_size.x * 2.0 - 1.0, 1.0 - px.y / u_size.y * 2.0, 0.0, 1.0);
}
