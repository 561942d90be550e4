#version 450 core
// The line kit's GPU culling, per chunk after phase 1: the depth test against the depth
// pyramid (line_depth_pyramid.comp, the farthest depth per tile and level). A chunk not drawn
// in phase 1 whose box on screen lies behind every texel it covers is occluded; otherwise
// phase 2 draws it. What the test does not hide (drawn in either phase) is next frame's
// phase 1. With u_cull_remember (a frame without history: everything was drawn in phase 2) only
// that last part runs, against the final depth.
#define CULL_USES_STATE
#include "line_cull.glsl"

layout(local_size_x = CULL_GROUP) in;

uniform uint u_cull_chunks;
uniform sampler2D u_cull_pyramid;  // level 0: CULL_TILE x CULL_TILE pixels a texel
uniform ivec2 u_cull_pixels;       // the depth buffer's size
uniform int u_cull_remember;

// Hidden: every texel the rectangle touches (one pixel more on each side, for the raster)
// holds only nearer depths than the box's nearest.
bool hidden(vec4 rect, float zmin) {
    vec2 size = vec2(u_cull_pixels);
    ivec2 a = clamp(ivec2(floor((rect.xy * 0.5 + 0.5) * size)) - 1, ivec2(0), u_cull_pixels - 1) / CULL_TILE;
    ivec2 b = clamp(ivec2(ceil((rect.zw * 0.5 + 0.5) * size)) + 1, ivec2(0), u_cull_pixels - 1) / CULL_TILE;
    // The finest level where the rectangle covers at most CULL_TEST_TEXELS texels (a texel of
    // level k covers 2^k of level 0's a side, the last one of a row or column also what an odd
    // size leaves): long thin boxes stay on fine levels, where a coarse texel would reach past
    // the lines in front.
    int levels = textureQueryLevels(u_cull_pyramid), level = 0;
    while (level + 1 < levels && (b.x - a.x + 1) * (b.y - a.y + 1) > CULL_TEST_TEXELS) {
        a >>= 1;
        b >>= 1;
        ++level;
    }
    ivec2 last = textureSize(u_cull_pyramid, level) - 1;
    a = min(a, last);
    b = min(b, last);
    for (int y = a.y; y <= b.y; ++y)
        for (int x = a.x; x <= b.x; ++x)
            if (texelFetch(u_cull_pyramid, ivec2(x, y), level).r >= zmin) return false;
    return true;
}

void main() {
    uint c = gl_GlobalInvocationID.x;
    if (c >= u_cull_chunks) return;
    uint f = cull_state[c].flags;
    if ((f & kCullDrawn) == 0u || (f & kCullOutside) != 0u) return;
    bool h = (f & kCullTestable) != 0u && hidden(cull_state[c].rect, cull_state[c].zmin);
    if (u_cull_remember != 0) {
        f &= ~kCullVisible;
        if ((f & (kCullPhase1 | kCullPhase2)) != 0u && !h) f |= kCullVisible;
    } else if ((f & kCullPhase1) != 0u) {
        if (!h) f |= kCullVisible;
    } else {
        f |= h ? kCullOccluded : (kCullPhase2 | kCullVisible);
    }
    cull_state[c].flags = f;
}
