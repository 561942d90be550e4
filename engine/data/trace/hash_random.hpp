// Stateless, platform-independent pseudo-random numbers from a key (splitmix64), so a
// value depends only on what it is for (voxel index, seed), never on call order or thread.
#pragma once

#include <cstdint>

namespace pathlet::trace {

inline uint64_t hash64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}
inline uint64_t hash64(uint64_t a, uint64_t b) { return hash64(a ^ hash64(b)); }

// Uniform in [0, 1) from the top 24 bits (exact in float).
inline float unit_float(uint64_t h) { return float(h >> 40) * (1.0f / 16777216.0f); }

}  // namespace pathlet::trace
