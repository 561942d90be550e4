#version 450 core
// Illuminated streamlines (Zoeckler et al. 1996): Phong lighting maximised over the normals
// around the tangent, so it needs only T. L and V point away from the surface.
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"
#include "pow_whole.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the pass's hook (default: the colour as it is)

uniform vec3 u_light;  // towards the light, view space, unit (from light_dir)
// The pass's parameters, by declaration:
uniform float u_ambient, u_diffuse, u_specular;
uniform float u_exponent;          // specular exponent n
uniform float u_diffuse_exponent;

layout(location = 0) out vec4 o_color;
#ifdef WRITE_EDGE
layout(location = 1) out vec4 o_edge;  // the rim for edge_aa
#endif

void main() {
    LineFrag f = line_fragment();
    vec4 c = line_color_hook(vec4(f.color, 1.0), f.point);
#ifndef LINE_OPAQUE  // the default colour hook is opaque: no screen door, no discard
    if (c.a < line_screen_door_threshold(gl_FragCoord.xy)) discard;
#endif
    float lt = dot(u_light, f.tangent), vt = dot(f.to_viewer, f.tangent);
    float sl = sqrt(max(1.0 - lt * lt, 0.0)), sv = sqrt(max(1.0 - vt * vt, 0.0));
    // Whole exponents (the defaults 1 and 50) are built into the program (isl.cpp): products, not pow.
#ifdef ISL_DIFFUSE_EXPONENT
    float diffuse = pow_whole(sl, ISL_DIFFUSE_EXPONENT);
#else
    float diffuse = pow(sl, u_diffuse_exponent);
#endif
#ifdef ISL_SPECULAR_EXPONENT
    float specular = pow_whole(max(sl * sv - lt * vt, 0.0), ISL_SPECULAR_EXPONENT);
#else
    float specular = pow(max(sl * sv - lt * vt, 0.0), u_exponent);
#endif
    vec3 lit = c.rgb * (u_ambient + u_diffuse * diffuse) + vec3(u_specular * specular);
    o_color = vec4(line_halo_tint(clamp(lit, 0.0, 1.0), f), 1.0);
#ifdef WRITE_EDGE
    o_edge = line_edge(f);
#endif
    gl_FragDepth = line_window_depth(f.depth01);
}
