#version 450 core
// One level of the line kit's depth pyramid (engine/lines/src/chunk_culler.hpp): the farthest
// depth of CULL_TILE x CULL_TILE pixels of the depth buffer (level 0, CULL_PYRAMID_BASE), or of
// 2 x 2 texels of the level below. The last texel of a row or column also takes what an odd
// size leaves over, so every level covers every pixel.
layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D u_cull_source;  // the depth buffer, or the pyramid (level u_cull_level - 1)
uniform int u_cull_level;         // the level written
layout(r32f) writeonly uniform image2D u_cull_target;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy), size = imageSize(u_cull_target);
    if (any(greaterThanEqual(p, size))) return;
#ifdef CULL_PYRAMID_BASE
    const int span = CULL_TILE;
    int lod = 0;
#else
    const int span = 2;
    int lod = u_cull_level - 1;
#endif
    ivec2 last = textureSize(u_cull_source, lod) - 1;
    ivec2 lo = p * span, hi = lo + span - 1;
    if (p.x == size.x - 1) hi.x = last.x;
    if (p.y == size.y - 1) hi.y = last.y;
    hi = min(hi, last);
    float m = 0.0;
#ifdef CULL_PYRAMID_BASE
    // 2x2 texels a gather (at the corner between them); one past the edge wraps around, which
    // only makes the farthest depth farther (conservative).
    vec2 inv = 1.0 / vec2(last + 1);
    for (int y = lo.y; y <= hi.y; y += 2)
        for (int x = lo.x; x <= hi.x; x += 2) {
            vec4 g = textureGather(u_cull_source, (vec2(x, y) + 1.0) * inv);
            m = max(m, max(max(g.x, g.y), max(g.z, g.w)));
        }
#else
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) m = max(m, texelFetch(u_cull_source, ivec2(x, y), lod).r);
#endif
    imageStore(u_cull_target, p, vec4(m));
}
