#version 450 core
// Depth- and normal-aware (cross-bilateral) smoothing of the AO term, multiplied into the
// colour. Background pixels (colour alpha 0) are copied unchanged. Separable mode runs it
// twice (horizontal into `tmp`, vertical with the multiply): 2(2r+1) taps instead of (2r+1)^2. Uniform loop bounds:
// on llvmpipe they skip the fetches of background pixels instead of running them masked.
#include "fullscreen_pass.glsl"
#include "lineao_common.glsl"
#include "pow_whole.glsl"

uniform bool u_multiply;  // last pass: write colour * ao (final); else the filtered ao alone (tmp)

// The outputs: `final` (colour x AO) or, in the separable mode's first pass, `tmp` (the
// filtered AO alone); with WRITE_AO also `ao_smooth`, the smoothed AO alone.
#ifdef FULLSCREEN_COMPUTE
layout(rgba8) writeonly uniform image2D u_final;
layout(r16f) writeonly uniform image2D u_tmp;
void write_color(ivec2 p, vec4 c) {
    if (u_multiply) imageStore(u_final, p, c);
    else imageStore(u_tmp, p, c);
}
#ifdef WRITE_AO
layout(r16f) writeonly uniform image2D u_ao_smooth;
void write_ao(ivec2 p, float ao) {
    if (u_multiply) imageStore(u_ao_smooth, p, vec4(ao));
}
#endif
#else
layout(location = 0) out vec4 o_color;
void write_color(ivec2 p, vec4 c) { o_color = c; }
#ifdef WRITE_AO
layout(location = 1) out float o_ao;  // the smoothed AO alone (last pass), for per-fragment use
void write_ao(ivec2 p, float ao) { o_ao = ao; }
#endif
#endif
uniform sampler2D u_ao;     // LineAO's term; in the vertical pass of the separable mode, `tmp`
uniform sampler2D u_normal_depth;
uniform sampler2D u_color;
uniform int u_radius;       // pixels (times the pixel scale)
uniform float u_inv2_sigma_s2;  // 1 / (2 sigma_spatial^2)
uniform float u_inv_sigma_d;    // 1 / sigma_depth
uniform float u_normal_power;  // only when not whole (BILATERAL_NORMAL_POWER) nor 0 (BILATERAL_NO_NORMAL)
uniform bool u_enabled;
uniform ivec2 u_step;      // (1,0) or (0,1): one axis of the separable filter; (0,0): full 2-D

void main() {
    ivec2 p;
    if (!fullscreen_pixel(p)) return;
    vec4 c = texelFetch(u_color, p, 0);
    if (c.a == 0.0) {  // background: exactly the colour pass's pixel
        write_color(p, c);
#ifdef WRITE_AO
        write_ao(p, 1.0);
#endif
        return;
    }
    vec4 nd = texelFetch(u_normal_depth, p, 0);
    float ao = texelFetch(u_ao, p, 0).r;
    if (u_enabled && nd_is_geometry(nd)) {
        vec3 n = normalize(nd.xyz);
        ivec2 size = textureSize(u_ao, 0);
        float sum = 0.0, wsum = 0.0;
        // Separable: 2r+1 taps along u_step; full: (2r+1)^2 taps.
        int rj = u_step == ivec2(0) ? u_radius : 0;
        ivec2 axis = u_step == ivec2(0) ? ivec2(1, 0) : u_step;
        for (int j = -rj; j <= rj; ++j)
            for (int i = -u_radius; i <= u_radius; ++i) {
                ivec2 q = p + axis * i + ivec2(0, j);
                if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
                vec4 o = texelFetch(u_normal_depth, q, 0);
                if (!nd_is_geometry(o)) continue;  // background AO (= 1) must not brighten edges
                float dz = (o.w - nd.w) * u_inv_sigma_d;
                float w = exp(-float(i * i + j * j) * u_inv2_sigma_s2 - dz * dz);
                // The power is compiled in (bilateral.cpp): llvmpipe runs both sides of a select,
                // so `power == 1 ? c : pow(c, power)` paid for a pow on every tap.
#if defined(BILATERAL_NORMAL_POWER)
                w *= pow_whole(max(dot(n, normalize(o.xyz)), 0.0), BILATERAL_NORMAL_POWER);
#elif !defined(BILATERAL_NO_NORMAL)
                w *= pow(max(dot(n, normalize(o.xyz)), 0.0), u_normal_power);
#endif
                sum += w * texelFetch(u_ao, q, 0).r;
                wsum += w;
            }
        if (wsum > 1e-6) ao = sum / wsum;  // the centre always has weight 1 unless its normal is 0
    }
    write_color(p, u_multiply ? vec4(c.rgb * ao, c.a) : vec4(ao));
#ifdef WRITE_AO
    write_ao(p, ao);
#endif
}
