// Shared by gauss_pyramid, lineao and bilateral: how the normal_depth G-buffer encodes
// "no geometry", and a deterministic integer hash for per-pixel noise.
// normal_depth: xyz = view-space unit normal, w = linear depth normalised over [near, far];
// background: normal 0, w = 1.
#ifndef LINEAO_COMMON_GLSL
#define LINEAO_COMMON_GLSL

const vec4 ND_BACKGROUND = vec4(0.0, 0.0, 0.0, 1.0);

// The normal decides, not the depth: a line may legitimately sit at w = 1 (far plane,
// pushed-back halos). Box-filtered mips shorten normals at edges; 0.01 keeps those.
bool nd_is_geometry(vec4 nd) { return dot(nd.xyz, nd.xyz) > 0.01; }

// PCG-style 32-bit hash (Jarzynski & Olano 2020): same value on every run and driver.
uint lineao_hash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
uint lineao_hash3(uvec3 v) { return lineao_hash(v.x ^ lineao_hash(v.y ^ lineao_hash(v.z))); }
// Two uniform numbers in [0,1) from one hash.
vec2 lineao_rand2(uint h) { return vec2(h & 0xffffu, h >> 16u) * (1.0 / 65536.0); }

#endif
