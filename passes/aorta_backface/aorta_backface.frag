#version 450 core
// Quiet, lit context: the wall's back faces (the far side of the vessel, seen through it) or
// the whole wall, headlight-shaded and blended at low opacity over the finished image where
// no line is in front (the G-buffer depth test). LineAO never sees the wall, so it darkens no
// line (the study's Fig. 11c).
in vec3 v_normal;
in vec3 v_pos;
uniform vec3 u_wall_color;  // the pass's parameters, by declaration
uniform int u_mode;         // 0: backfaces, 1: whole
uniform float u_normal_sign;  // +1: the mesh's normals point outward, -1: inward
layout(location = 0) out vec4 o_color;
#ifdef CLEAR_SHOWS_WALL  // the depth test in here: a line hides the wall only where the image shows one
uniform sampler2D u_depth;  // the pins, by declaration
uniform sampler2D u_color;
#endif
void main() {
#ifdef CLEAR_SHOWS_WALL
    const ivec2 px = ivec2(gl_FragCoord.xy);
    if (gl_FragCoord.z >= texelFetch(u_depth, px, 0).r && texelFetch(u_color, px, 0).a > 0.0) discard;
#endif
    vec3 n = u_normal_sign * normalize(v_normal);
    vec3 to_eye = normalize(-v_pos);
    float facing = dot(n, to_eye);  // > 0: the side towards the viewer (outward normals)
    if (u_mode == 0 && facing > 0.0) discard;
    float shade = 0.55 + 0.45 * abs(facing);
    o_color = vec4(u_wall_color * shade, 1.0);  // blended at the pass's opacity (a blend constant)
}
