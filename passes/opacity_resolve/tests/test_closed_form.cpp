// opacity_resolve on real GL: a stack of four overlapping straight lines (one segment each) of
// known importance; every segment's opacity must be the closed form computed on the CPU from
// the very fragments of opacity_lists' lists (1e-3), and the closed form of the whole stack.
// adapt = depth_complexity: q and r scale with the lists' mean fragments per covered pixel,
// counted on the CPU from the same lists; a stack twice as deep clears twice as strongly.
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
// `layers` lines, the k-th at z = -k with the importance kSpeed[k % 4] / 100.
Scene stack_of(int layers) {
    std::vector<StraightLine> l;
    for (int k = 0; k < layers; ++k) l.push_back({{0, 2, -float(k)}, {10, 2, -float(k)}, kSpeed[k % 4], 41, {}});
    return straight_lines_scene(l);
}
const Scene& stack() {
    static const Scene s = stack_of(4);
    return s;
}

std::vector<std::string> sets(int max_fragments, const std::string& adapt = "fixed") {
    return {"window=-1", "line_width=0.8", "opacity_lists.importance_min=0", "opacity_lists.importance_max=100",
            "importance_exponent=1", "segment_length=1000", "q=" + std::to_string(kQ), "r=" + std::to_string(kR),
            "lambda=" + std::to_string(kLambda), "opacity_resolve.max_fragments=" + std::to_string(max_fragments),
            "adapt=" + adapt};
}

// `scale`: the factor of q and r (adapt).
double closed_form(double g, double front, double behind, double scale = 1.0) {
    return 1.0 / (1.0 + std::pow(1.0 - g, 2.0 * kLambda) * scale * (kR * front + kQ * behind));
}

struct Node {
    uint32_t segment;
    float depth, importance;
};

// The least closed-form opacity per segment over the lists, as opacity_resolve.comp defines it;
// `beyond`: fragments past the `keep` nearest.
std::map<uint32_t, double> cpu_targets(const std::vector<uint32_t>& lists, int keep, size_t& beyond, size_t& layered,
                                       double scale = 1.0) {
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
            const double a = closed_form(g, front, std::max(all - front - g2, 0.0), scale);
            front += g2;
            auto it = least.find(frags[k].segment);
            if (it == least.end() || a < it->second) least[frags[k].segment] = a;
        }
    }
    return least;
}

// The lists' depth complexity counted on the CPU: covered pixels and their fragments.
struct Depth {
    uint64_t pixels = 0, fragments = 0;
    double mean() const { return pixels ? double(fragments) / double(pixels) : 0.0; }
};
Depth cpu_depth(const std::vector<uint32_t>& lists) {
    const uint32_t w = lists.at(3), h = lists.at(4);
    const uint32_t nodes_at = (8 + w * h + 3) & ~3u;
    Depth d;
    for (uint32_t p = 0; p < w * h; ++p) {
        uint64_t n = 0;
        for (uint32_t i = lists.at(8 + p); i != 0xFFFFFFFFu; i = lists.at(nodes_at + 4 * i + 3)) ++n;
        d.pixels += n > 0;
        d.fragments += n;
    }
    return d;
}

// opacity_resolve's density words (opacity_resolve.comp): pixels, fragments (64 bits), scale.
struct Density {
    uint64_t pixels = 0, fragments = 0;
    float scale = 0.0f;
};
Density gpu_density(const FrameRunner& run) {
    const std::vector<uint32_t> w = run.words("opacity_resolve.density");
    return {w.at(0) | uint64_t(w.at(1)) << 32, w.at(2) | uint64_t(w.at(3)) << 32, as_float(w.at(4))};
}

struct Adapted {
    Depth cpu;
    Density gpu;
};
// One frame of a `layers`-deep stack with adapt = depth_complexity; every segment's opacity must
// be the closed form with q and r times the scale the CPU expects from the lists' depth.
Adapted adapted_stack(int layers, const std::vector<std::string>& extra, double expected_scale_per_depth) {
    const Scene scene = stack_of(layers);
    std::vector<std::string> s = sets(64, "depth_complexity");
    s.insert(s.end(), extra.begin(), extra.end());
    FrameRunner run(kGraph, s, scene, kSize, camera_down_z(scene, {5, 2, 0}, 30, 30, kSize),
                    {"oo_lists", "oo_segments", "oo_targets"});
    run.frame(0.0);
    const std::vector<uint32_t> lists = run.words("oo_lists"), targets = run.words("oo_targets");
    Adapted a{cpu_depth(lists), gpu_density(run)};
    size_t beyond = 0, layered = 0;
    const double scale = expected_scale_per_depth > 0 ? expected_scale_per_depth * a.cpu.mean() : double(a.gpu.scale);
    const std::map<uint32_t, double> cpu = cpu_targets(lists, 64, beyond, layered, scale);
    EXPECT_EQ(cpu.size(), size_t(layers));
    for (const auto& [segment, alpha] : cpu) {
        EXPECT_NE(target_bits(targets, segment), kUnseen) << "segment " << segment;
        EXPECT_NEAR(as_float(target_bits(targets, segment)), alpha, 1e-3) << layers << " layers, segment " << segment;
    }
    return a;
}

}  // namespace

// q and r times D / depth_reference, D = fragments per covered pixel, counted on the GPU over
// the very lists the CPU counts; a denser input (eight layers for four) clears more strongly.
TEST(OpacityResolve, AdaptScalesQAndRWithTheDepthComplexityOfTheLists) {
    const double reference = 2.0;
    const std::vector<std::string> extra = {"depth_reference=" + std::to_string(reference),
                                            "opacity_resolve.adapt_min=0", "opacity_resolve.adapt_max=1000"};
    const Adapted sparse = adapted_stack(4, extra, 1.0 / reference), dense = adapted_stack(8, extra, 1.0 / reference);
    for (const Adapted* a : {&sparse, &dense}) {
        EXPECT_EQ(a->gpu.pixels, a->cpu.pixels) << "covered pixels";
        EXPECT_EQ(a->gpu.fragments, a->cpu.fragments) << "fragments";
        EXPECT_NEAR(a->gpu.scale, a->cpu.mean() / reference, 1e-5 * a->gpu.scale);
    }
    EXPECT_GT(sparse.cpu.mean(), 3.0) << "most covered pixels see the whole stack";
    EXPECT_GT(dense.cpu.mean(), 1.8 * sparse.cpu.mean()) << "twice the layers over the same pixels";
    EXPECT_NEAR(dense.gpu.scale / sparse.gpu.scale, dense.cpu.mean() / sparse.cpu.mean(), 1e-4);
}

// The scale stays within [adapt_min, adapt_max] (the graph's default: at least a quarter of q
// and r), and adapt = fixed uses q and r as given, measuring nothing.
TEST(OpacityResolve, AdaptClampsItsScaleAndFixedUsesQAndRAsGiven) {
    const Adapted high = adapted_stack(4, {"depth_reference=0.01", "opacity_resolve.adapt_max=3"}, 0.0);
    EXPECT_FLOAT_EQ(high.gpu.scale, 3.0f);
    const Adapted low = adapted_stack(4, {"depth_reference=10000"}, 0.0);
    EXPECT_FLOAT_EQ(low.gpu.scale, 0.25f) << "the default adapt_min";
    EXPECT_GT(low.cpu.mean(), 3.0);

    FrameRunner run(kGraph, sets(32), stack(), kSize, camera_down_z(stack(), {5, 2, 0}, 30, 30, kSize),
                    {"oo_lists", "oo_segments", "oo_targets"});
    run.frame(0.0);
    const Density fixed = gpu_density(run);
    EXPECT_FLOAT_EQ(fixed.scale, 1.0f);
    EXPECT_EQ(fixed.pixels, 0u) << "adapt = fixed: no measuring dispatch";
}

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
