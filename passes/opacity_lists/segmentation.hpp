// Opacity optimization's segments on the CPU: every line cut by arc length into segments of
// about `length` each (at least one), with a value per segment from a per-point field (speed or
// a point array), normalised to [0, 1] on a fixed range. Laid out as
// shaders/opacity_optimization.glsl says (header, line table, per-segment words).
#pragma once

#include <pathlet/scene.hpp>

#include <cstdint>
#include <vector>

namespace opacity_lists {

// The header's size and the work group its dispatch counts are for (OO_HEADER_WORDS, OO_GROUP).
constexpr uint32_t kHeaderWords = 8, kGroup = 64;

struct Segmentation {
    std::vector<uint32_t> first, count;  // per line
    std::vector<float> length;           // per line: its segment length (0 for a zero-length line)
    std::vector<uint32_t> line;          // per segment
    size_t segments() const { return line.size(); }
};

// Arc length from each line's first point, per point (as GpuScene measures it for the kit).
std::vector<float> arc_lengths(const pathlet::Pathlines& lines);
// Segments of about `length` (> 0) world units along each line.
Segmentation segment_lines(const pathlet::Pathlines& lines, const std::vector<float>& arc, float length);
// Per segment, the arc-length mean of the piecewise-linear field `value` (one per point) over it.
std::vector<float> segment_means(const pathlet::Pathlines& lines, const std::vector<float>& arc,
                                 const Segmentation& s, const std::vector<float>& value);
// The p-th quantile (0..1) of the finite values.
float quantile(std::vector<float> v, double p);

// The buffer of shaders/opacity_optimization.glsl: header, line table, each segment's line and,
// when `importance` is given (one per segment, in [0, 1]), the importances after them.
std::vector<uint32_t> pack(const Segmentation& s, uint32_t generation, const std::vector<float>* importance);

}  // namespace opacity_lists
