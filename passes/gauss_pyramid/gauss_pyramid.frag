#version 450 core
// One level of the normal/depth pyramid. u_src is the previous level (a one-level view of it,
// so the level being written is never a sampled level: no feedback loop), or the input.
#include "fullscreen_pass.glsl"
#include "lineao_common.glsl"

#ifdef FULLSCREEN_COMPUTE
layout(rgba16f) writeonly uniform image2D u_pyramid;  // bound to the level being written
void write_nd(ivec2 p, vec4 nd) { imageStore(u_pyramid, p, nd); }
#else
layout(location = 0) out vec4 o_nd;
void write_nd(ivec2 p, vec4 nd) { o_nd = nd; }
#endif
uniform sampler2D u_src;
uniform int u_mode;  // 0 copy (level 0), 1 Gaussian, 2 box

// [1 3 3 1]/8 is the binomial kernel centred between two fine texels, i.e. on the coarse
// texel's centre; its 4x4 outer product is the 2D Gaussian-like downsample.
const float W4[4] = float[4](1.0, 3.0, 3.0, 1.0);

void main() {
    ivec2 p;
    if (!fullscreen_pixel(p)) return;
    if (u_mode == 0) {
        write_nd(p, texelFetch(u_src, p, 0));
        return;
    }
    ivec2 fine = textureSize(u_src, 0);
    ivec2 base = 2 * p;
    if (u_mode == 2) {
        // glGenerateMipmap's box filter, background included (OpenWalnut's "pyramid").
        vec4 s = vec4(0.0);
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) s += texelFetch(u_src, min(base + ivec2(i, j), fine - 1), 0);
        write_nd(p, 0.25 * s);
        return;
    }
    // Coverage follows the 2x2 children (as in box mips): a texel whose children are all
    // background stays background, so lines are not dilated level by level, and the (mostly
    // background) texels cost 4 fetches instead of 16.
    bool covered = false;
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) covered = covered || nd_is_geometry(texelFetch(u_src, min(base + ivec2(i, j), fine - 1), 0));
    if (!covered) {
        write_nd(p, ND_BACKGROUND);
        return;
    }
    vec4 sum = vec4(0.0);
    float wsum = 0.0;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            vec4 nd = texelFetch(u_src, clamp(base + ivec2(i - 1, j - 1), ivec2(0), fine - 1), 0);
            // Background texels are left out and the weights renormalised, so lines do not
            // bleed into the background and their depth is not pulled towards w = 1.
            float w = nd_is_geometry(nd) ? W4[i] * W4[j] : 0.0;
            sum += w * nd;
            wsum += w;
        }
    sum /= wsum;  // > 0: a covered child has weight >= 3*3
    // Opposite normals (two sides of a thin tube) may cancel: fall back to facing the viewer.
    float len = length(sum.xyz);
    write_nd(p, vec4(len > 1e-4 ? sum.xyz / len : vec3(0.0, 0.0, 1.0), sum.w));
}
