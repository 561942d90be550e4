#pragma once
// `pathlet quality GRAPH --transparency` as a function (also pathlet.transparency in Python):
// what the transparency of an OIT graph (resolve_list over fill_list's lists) shows, measured
// on the very fragments of its lists, read back after every frame. Each fragment is placed on
// its line's data segment (its pixel and depth unprojected, the nearest segment of its line in
// the window); per segment and frame: footprint A (fragments), ink V (alpha x the transmittance
// in front of it, what reaches the picture), unoccludedness U (the transmittance) and its mean
// opacity. Focus: the fastest focus_share of the data's segments (a fixed speed threshold over
// the whole data set, so the focus does not change with the frame); context: the rest.
//   focus visibility   sum V / sum A over focus fragments, and unoccluded sum U / sum A
//   focus ink share    sum V over focus / sum V over all
//   context coverage   share of the context segments seen in a frame whose V / A >= threshold
//   alpha change       |mean opacity(t) - mean opacity(t-1)| per segment seen in both frames
//   overflow           fragments lost to full node buffers or beyond a resolve's max_fragments,
//                      in the final lists and in opacity optimization's lists
//   pixel coverage     mean composited alpha over the pixels with fragments
#include "renderer.hpp"
#include "runtime.hpp"

#include <pathlet/scene.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace pathlet::quality {

struct TransparencyOptions {
    std::string graph_path;
    std::vector<std::string> sets;
    glm::ivec2 size{320, 180};
    // At least two frames (or repeat > 1: a frozen view); none: default_quality_time(scene), said on stderr.
    std::optional<TimeRange> time;
    int repeat = 1;              // frames per time
    double focus_share = 0.1;    // the most important share of the data's segments (by speed)
    double threshold = 0.05;     // context coverage: ink per footprint pixel that counts as seen
};

struct TransparencyResult {
    std::string graph;
    std::string not_measured;  // non-empty: why this graph has nothing to measure
    size_t frames = 0;
    double first_time = 0, last_time = 0;
    double focus_visibility = 0, focus_unoccluded = 0, focus_ink_share = 0, context_coverage = 0;
    double alpha_change_mean = 0, alpha_change_p95 = 0, alpha_change_max = 0;
    double pixel_coverage = 0;
    uint64_t overflow = 0;
    double focus_speed = 0;                  // the speed from which a segment is focus
    size_t fragments = 0, located = 0;       // fragments read, and placed on a data segment
    size_t focus_footprint = 0, context_seen = 0;
    std::vector<double> max_alpha_change_per_frame;  // frame k vs k-1 (k >= 1)
};

// Throws GraphError (bad graph or --set), std::invalid_argument (fewer than two frames).
TransparencyResult measure_transparency(Runtime& rt, const Scene& scene, const TransparencyOptions& opt);
void check_transparency_options(const TransparencyOptions& opt);

// One fragment of a pixel's list as the measures use it.
struct Fragment {
    float depth = 0;     // linear depth01
    uint32_t line = 0;   // line id
    uint32_t color = 0;  // packUnorm4x8 (ties, as resolve_list orders)
    float alpha = 0;
    int64_t segment = -1;  // data segment (its first point's index), -1: not placed
};
// Per-segment sums of one frame (indexed by the segment's first point).
struct SegmentSums {
    std::vector<double> ink, unoccluded, alpha;
    std::vector<uint32_t> footprint;
    std::vector<uint32_t> seen;  // segments with footprint > 0, in first-seen order
    explicit SegmentSums(size_t points = 0) : ink(points), unoccluded(points), alpha(points), footprint(points) {}
    void clear();
};
// Composites one pixel as resolve_list does (sorted by depth, line id, colour; the `keep`
// nearest; front to back until alpha >= 0.99) and adds every kept fragment to its segment's
// sums. Returns the pixel's composited alpha.
double composite_pixel(std::vector<Fragment>& frags, int keep, SegmentSums& sums);

}  // namespace pathlet::quality
