#version 450 core
// Half-resolution LineAO back to full resolution, depth-aware (joint bilateral upsampling): a
// pixel takes the half-res terms of the four nearest blocks, bilinearly weighted and weighted
// by how close the depth and normal of each block's pixel are to its own, so AO does not bleed
// across line edges. (A sharper normal weight, cos^16, measured worse on the phantom: 2.94 vs
// 2.76/255 in the final image.) Runs only on geometry (the G-buffer depth test); the background stays 1.
#include "fullscreen_pass.glsl"
#include "lineao_common.glsl"

#ifdef FULLSCREEN_COMPUTE
layout(r16f) writeonly uniform image2D u_ao;
void write_ao(ivec2 p, float ao) { imageStore(u_ao, p, vec4(ao)); }
#else
layout(location = 0) out float o_ao;
void write_ao(ivec2 p, float ao) { o_ao = ao; }
#endif
uniform sampler2D u_normal_depth;  // full-res normal + linear depth
uniform sampler2D u_half;          // half-res AO (lineao's internal texture): texel h holds full-res pixel 2h
uniform float u_inv_sigma_d;                   // 1 / depth tolerance (normalised linear depth)

void main() {
    ivec2 p;
    if (!fullscreen_pixel(p)) return;
    vec4 nd = texelFetch(u_normal_depth, p, 0);
    ivec2 hs = textureSize(u_half, 0);
    ivec2 full = textureSize(u_normal_depth, 0);
    // Position in half-res texel units, relative to texel centres at 2h.
    vec2 f = vec2(p) * 0.5;
    ivec2 h0 = ivec2(floor(f));
    vec2 t = f - vec2(h0);
    float sum = 0.0, wsum = 0.0;
    for (int j = 0; j <= 1; ++j)
        for (int i = 0; i <= 1; ++i) {
            ivec2 h = clamp(h0 + ivec2(i, j), ivec2(0), hs - 1);
            ivec2 src = min(h * 2, full - 1);
            vec4 o = texelFetch(u_normal_depth, src, 0);
            if (!nd_is_geometry(o)) continue;
            float wb = (i == 0 ? 1.0 - t.x : t.x) * (j == 0 ? 1.0 - t.y : t.y) + 1e-3;
            float dz = (o.w - nd.w) * u_inv_sigma_d;
            float w = wb * exp(-dz * dz) * max(dot(normalize(o.xyz), normalize(nd.xyz)), 0.05);
            sum += w * texelFetch(u_half, h, 0).r;
            wsum += w;
        }
    write_ao(p, wsum > 1e-6 ? sum / wsum : texelFetch(u_half, clamp(p / 2, ivec2(0), hs - 1), 0).r);
}
