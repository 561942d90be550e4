// The buffers of opacity optimization (shaders/opacity_optimization.glsl) read on the CPU, for
// the tests of opacity_lists, opacity_resolve and opacity_blend.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

namespace pathlet::oo_test {

inline float as_float(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

// The layouts of shaders/opacity_optimization.glsl, read on the CPU.
struct Segments {
    uint32_t lines = 0, segments = 0, per_segment = 0;
    std::vector<uint32_t> w;
    explicit Segments(std::vector<uint32_t> words) : w(std::move(words)) {
        lines = w.at(0), segments = w.at(1), per_segment = w.at(3);
    }
    uint32_t first(uint32_t l) const { return w.at(8 + 4 * l); }
    uint32_t count(uint32_t l) const { return w.at(8 + 4 * l + 1); }
    uint32_t line_of(uint32_t s) const { return w.at(per_segment + s); }
    uint32_t left(uint32_t s) const { return s > first(line_of(s)) ? s - 1 : s; }
    uint32_t right(uint32_t s) const { return s + 1 < first(line_of(s)) + count(line_of(s)) ? s + 1 : s; }
};
constexpr uint32_t kUnseen = 0xFFFFFFFFu;
// opacity_resolve's least opacity of segment s (kUnseen: no fragment).
inline uint32_t target_bits(const std::vector<uint32_t>& targets, uint32_t s) { return targets.at(8 + s); }

}  // namespace pathlet::oo_test
