#version 450 core
// The line kit's occlusion culling reads this back (engine/lines/src/chunk_culler.hpp): the
// farthest depth of each 8x8-pixel tile of a pass's depth buffer, one texel per tile.
uniform sampler2D u_tile_source;  // the depth buffer (bound by lines::Drawer)
layout(location = 0) out float o_farthest;
void main() {
    ivec2 base = ivec2(gl_FragCoord.xy) * 8, last = textureSize(u_tile_source, 0) - 1;
    float m = 0.0;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) m = max(m, texelFetch(u_tile_source, min(base + ivec2(x, y), last), 0).r);
    o_farthest = m;
}
