// opacity_resolve on real GL: a stack of four overlapping straight lines (one segment each) of
// known importance; every segment's opacity must be the closed form computed on the CPU from
// the very fragments of opacity_lists' lists (1e-3), and the closed form of the whole stack.
#include "frame_runner.hpp"
#include "opacity_layout.hpp"
#include "straight_lines.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

using namespace pathlet;
using namespace pathlet::oo_test;

namespace {

const std::string kGraph = std::string(PATHLET_SOURCE_DIR) + "/graphs/variant4_opacity.json";
const glm::ivec2 kSize{160, 120};
const double kQ = 2.0, kR = 1.0, kLambda = 1.5;
const float kSpeed[4] = {20, 40, 60, 90};  // importance 0.2, 0.4, 0.6, 0.9 on [0, 100]

// Front (z = 0) to back (z = -3), all over the same pixels, along x.
const Scene& stack() {
    static const Scene s = [] {
        std::vector<StraightLine> l;
        for (int k = 0; k < 4; ++k) l.push_back({{0, 2, -float(k)}, {10, 2, -float(k)}, kSpeed[k], 41});
        return straight_lines_scene(l);
    }();
    return s;
}

std::vector<std::string> sets(int max_fragments) {
    return {"window=-1", "line_width=0.8", "opacity_lists.importance_min=0", "opacity_lists.importance_max=100",
            "importance_exponent=1", "segment_length=1000", "q=" + std::to_string(kQ), "r=" + std::to_string(kR),
            "lambda=" + std::to_string(kLambda), "opacity_resolve.max_fragments=" + std::to_string(max_fragments)};
}

double closed_form(double g, double front, double behind) {
    return 1.0 / (1.0 + std::pow(1.0 - g, 2.0 * kLambda) * (kR * front + kQ * behind));
}

struct Node {
    uint32_t segment;
    float depth, importance;
};

// The least closed-form opacity per segment over the lists, as opacity_resolve.comp defines it;
// `beyond`: fragments past the `keep` nearest.
std::map<uint32_t, double> cpu_targets(const std::vector<uint32_t>& lists, int keep, size_t& beyond, size_t& layered) {
    const uint32_t w = lists.at(3), h = lists.at(4);
    const uint32_t nodes_at = (8 + w * h + 3) & ~3u;
    std::map<uint32_t, double> least;
    for (uint32_t p = 0; p < w * h; ++p) {
        std::vector<Node> frags;
        for (uint32_t i = lists.at(8 + p); i != 0xFFFFFFFFu; i = lists.at(nodes_at + 4 * i + 3))
            frags.push_back({lists.at(nodes_at + 4 * i), as_float(lists.at(nodes_at + 4 * i + 1)),
                             as_float(lists.at(nodes_at + 4 * i + 2))});
        std::sort(frags.begin(), frags.end(), [](const Node& a, const Node& b) {
            return a.depth != b.depth ? a.depth < b.depth : a.segment < b.segment;
        });
        double all = 0, front = 0;
        for (const Node& f : frags) all += double(f.importance) * f.importance;
        layered += frags.size() == 4;
        if (frags.size() > size_t(keep)) beyond += frags.size() - size_t(keep);
        for (size_t k = 0; k < frags.size() && k < size_t(keep); ++k) {
            const double g = frags[k].importance, g2 = g * g;
            const double a = closed_form(g, front, std::max(all - front - g2, 0.0));
            front += g2;
            auto it = least.find(frags[k].segment);
            if (it == least.end() || a < it->second) least[frags[k].segment] = a;
        }
    }
    return least;
}

}  // namespace

TEST(OpacityResolve, ClosedFormPerSegmentEqualsTheCpuOverTheSameFragments) {
    FrameRunner run(kGraph, sets(32), stack(), kSize, camera_down_z(stack(), {5, 2, 0}, 30, 30, kSize),
                    {"oo_lists", "oo_segments", "oo_targets"});
    run.frame(0.0);
    const std::vector<uint32_t> lists = run.words("oo_lists"), targets = run.words("oo_targets");
    const Segments seg(run.words("oo_segments"));
    ASSERT_EQ(seg.segments, 4u) << "one segment per line";
    size_t beyond = 0, layered = 0;
    const std::map<uint32_t, double> cpu = cpu_targets(lists, 32, beyond, layered);
    EXPECT_GT(layered, 50u) << "low-resolution pixels with the whole stack";
    ASSERT_EQ(cpu.size(), 4u);
    double front = 0, all = 0;
    for (float v : kSpeed) all += (v / 100.0) * (v / 100.0);
    for (uint32_t s = 0; s < 4; ++s) {
        ASSERT_NE(target_bits(targets, s), kUnseen) << "segment " << s;
        const double gpu = as_float(target_bits(targets, s));
        EXPECT_NEAR(gpu, cpu.at(s), 1e-3) << "segment " << s;
        // Line s is the s-th layer of the stack: the closed form of the whole stack.
        const double g = kSpeed[seg.line_of(s)] / 100.0;
        EXPECT_NEAR(gpu, closed_form(g, front, all - front - g * g), 1e-3) << "segment " << s;
        front += g * g;
    }
    EXPECT_LT(as_float(target_bits(targets, 0)), 0.6) << "the front layer clears for the important ones behind";
    EXPECT_EQ(targets.at(0), 4u) << "segments that got fragments";
}

TEST(OpacityResolve, FragmentsBeyondMaxFragmentsStillOccludeButGetNoOpacity) {
    FrameRunner run(kGraph, sets(2), stack(), kSize, camera_down_z(stack(), {5, 2, 0}, 30, 30, kSize),
                    {"oo_lists", "oo_segments", "oo_targets"});
    run.frame(0.0);
    const std::vector<uint32_t> lists = run.words("oo_lists"), targets = run.words("oo_targets");
    size_t beyond = 0, layered = 0;
    const std::map<uint32_t, double> cpu = cpu_targets(lists, 2, beyond, layered);
    for (uint32_t s = 0; s < 2; ++s) EXPECT_NEAR(as_float(target_bits(targets, s)), cpu.at(s), 1e-3);
    // The two back lines have fragments only where they lie among a pixel's two nearest.
    EXPECT_EQ(targets.at(5), beyond) << "fragments beyond max_fragments, counted";
    EXPECT_GT(beyond, 100u);
}
