// opacity_blend on real GL: the smoothing along a line and the temporal blend against a CPU
// computation from opacity_resolve's own targets, frame-rate independence, a frozen view that
// converges, a jump back in time, and what a segment without fragments publishes.
#include "frame_runner.hpp"
#include "opacity_layout.hpp"
#include "straight_lines.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace pathlet;
using namespace pathlet::oo_test;

namespace {

const std::string kGraph = std::string(PATHLET_SOURCE_DIR) + "/graphs/variant4_opacity.json";
const glm::ivec2 kSize{160, 120};

// A curtain of 12 slow lines (speed 10) along x in front of one fast line (speed 100) across
// them along y near the right edge of the picture, so each curtain line clears where it crosses
// the fast one and nowhere else. Both run on off screen (the curtain to the right, the fast line
// upwards), so some segments get no fragment, among them the curtain's next to where it clears.
// Importance: speed on [0, 100], linear: 0.1 and 1.
const Scene& curtain() {
    static const Scene s = [] {
        std::vector<StraightLine> l;
        for (int k = 0; k < 12; ++k) l.push_back({{0, 0.5f * k, 0}, {40, 0.5f * k, 0}, 10.0f, 161});
        l.push_back({{25, -5, -3}, {25, 30, -3}, 100.0f, 141});
        return straight_lines_scene(l);
    }();
    return s;
}
// Sees x from about -4 to 28 (the curtain's right part is off screen).
Camera camera() { return camera_down_z(curtain(), {12, 2.75f, 0}, 45.0f, 30.0f, kSize); }

const std::vector<std::string> kSets = {"window=-1", "tail_fade=0", "head_fade=0", "line_width=0.6",
                                        "opacity_lists.importance_min=0", "opacity_lists.importance_max=100",
                                        "importance_exponent=1", "segment_length=2", "q=0", "r=0", "half_life=0.2",
                                        "smoothing=6", "adapt=fixed"};  // q and r as set (the blend's tests)
const std::vector<std::string> kKeep = {"oo_segments", "oo_targets", "oo_opacity"};

// The smoothing opacity_blend.comp does, on the CPU, from the targets.
std::vector<double> smoothed(const Segments& seg, const std::vector<uint32_t>& targets, int steps, double rate) {
    std::vector<double> v(seg.segments, 1.0);
    for (uint32_t s = 0; s < seg.segments; ++s)
        if (target_bits(targets, s) != kUnseen) v[s] = as_float(target_bits(targets, s));
    for (int k = 0; k < steps; ++k) {
        std::vector<double> next = v;
        for (uint32_t s = 0; s < seg.segments; ++s) {
            if (target_bits(targets, s) == kUnseen) continue;
            const uint32_t l = seg.left(s), r = seg.right(s);
            const double vl = target_bits(targets, l) != kUnseen ? v[l] : v[s];
            const double vr = target_bits(targets, r) != kUnseen ? v[r] : v[s];
            next[s] = v[s] + rate * (0.5 * (vl + vr) - v[s]);
        }
        v = next;
    }
    return v;
}

std::vector<float> published(const FrameRunner& run) {
    const std::vector<uint32_t> w = run.words("oo_opacity");
    const Segments seg(run.words("oo_segments"));
    std::vector<float> a(seg.segments);
    for (uint32_t s = 0; s < seg.segments; ++s) a[s] = as_float(w.at(seg.per_segment + s));
    return a;
}

}  // namespace

TEST(OpacityBlend, SmoothsAlongTheLineAndBlendsTowardsItWithTheHalfLife) {
    FrameRunner run(kGraph, kSets, curtain(), kSize, camera(), kKeep);
    run.frame(0.0);  // q = 0: nothing in the way of anything, every segment opaque
    for (float a : published(run)) ASSERT_FLOAT_EQ(a, 1.0f);
    run.set("opacity_resolve", "q", 60.0);
    run.frame(0.04);
    const Segments seg(run.words("oo_segments"));
    const std::vector<uint32_t> targets = run.words("oo_targets");
    const std::vector<double> s = smoothed(seg, targets, 6, 0.5);
    const double k = 1.0 - std::exp2(-0.04 / 0.2);
    const std::vector<float> a = published(run);
    size_t cleared = 0, seen = 0;
    for (uint32_t i = 0; i < seg.segments; ++i) {
        if (target_bits(targets, i) == kUnseen) continue;
        ++seen;
        cleared += s[i] < 0.9;
        EXPECT_NEAR(a[i], 1.0 + k * (s[i] - 1.0), 1e-5) << "segment " << i << " of line " << seg.line_of(i);
    }
    EXPECT_GT(seen, 100u);
    EXPECT_GT(cleared, 11u) << "every curtain line must clear where it crosses the fast one";
    // The smoothing is not the identity here: somewhere a segment moved towards its neighbours.
    double moved = 0;
    for (uint32_t i = 0; i < seg.segments; ++i)
        if (target_bits(targets, i) != kUnseen) moved = std::max(moved, std::fabs(s[i] - as_float(target_bits(targets, i))));
    EXPECT_GT(moved, 0.05);
}

TEST(OpacityBlend, TheBlendDependsOnTimeNotOnFrames) {
    auto after = [](int frames) {
        FrameRunner run(kGraph, kSets, curtain(), kSize, camera(), kKeep);
        run.frame(0.0);
        run.set("opacity_resolve", "q", 60.0);
        for (int f = 1; f <= frames; ++f) run.frame(0.4 * f / frames);
        return published(run);
    };
    const std::vector<float> at25 = after(10), at50 = after(20), at5 = after(2);
    ASSERT_EQ(at25.size(), at50.size());
    double diff = 0, change = 0;
    for (size_t i = 0; i < at25.size(); ++i) {
        diff = std::max({diff, double(std::fabs(at25[i] - at50[i])), double(std::fabs(at25[i] - at5[i]))});
        change = std::max(change, 1.0 - double(at25[i]));
    }
    EXPECT_LT(diff, 1e-5);
    EXPECT_GT(change, 0.3) << "the opacities must have moved for the comparison to mean anything";
}

TEST(OpacityBlend, AFrozenViewConvergesAndAJumpBackTakesTheNewValues) {
    FrameRunner run(kGraph, kSets, curtain(), kSize, camera(), kKeep);
    run.frame(1.0);
    run.set("opacity_resolve", "q", 60.0);
    std::vector<float> prev = published(run);
    double first = 0, last = 0, worst_increase = 0;
    for (int f = 0; f < 60; ++f) {
        run.frame(1.0);  // the clock stands still: each frame counts as 1/25 s
        const std::vector<float> a = published(run);
        double d = 0;
        for (size_t i = 0; i < a.size(); ++i) d = std::max(d, double(std::fabs(a[i] - prev[i])));
        if (f == 0) first = d;
        else worst_increase = std::max(worst_increase, d - last);
        last = d;
        prev = a;
    }
    EXPECT_GT(first, 0.05) << "the change of q must move the opacities";
    EXPECT_LT(last, 1e-4) << "max |d alpha| after 60 frozen frames";
    EXPECT_LE(worst_increase, first * 1e-3 + 1e-7) << "the change must shrink every frame, not oscillate";
    // Back to q = 0 and back in time: no history to keep, the new opacities at once.
    run.set("opacity_resolve", "q", 0.0);
    run.frame(0.5);
    for (float a : published(run)) ASSERT_NEAR(a, 1.0f, 1e-6);
}

TEST(OpacityBlend, ASegmentWithoutFragmentsTakesItsNeighboursOpacityOrOne) {
    FrameRunner run(kGraph, kSets, curtain(), kSize, camera(), kKeep);
    run.set("opacity_resolve", "q", 60.0);
    run.set("opacity_resolve", "r", 60.0);
    run.frame(0.0);
    const Segments seg(run.words("oo_segments"));
    const std::vector<uint32_t> targets = run.words("oo_targets");
    const std::vector<float> a = published(run);
    size_t unseen = 0, took_neighbour = 0, took_cleared = 0;
    for (uint32_t i = 0; i < seg.segments; ++i) {
        if (target_bits(targets, i) != kUnseen) continue;
        ++unseen;
        const bool left_seen = target_bits(targets, seg.left(i)) != kUnseen && seg.left(i) != i;
        const bool right_seen = target_bits(targets, seg.right(i)) != kUnseen && seg.right(i) != i;
        const float expect = left_seen ? a[seg.left(i)] : right_seen ? a[seg.right(i)] : 1.0f;
        took_neighbour += left_seen || right_seen;
        took_cleared += expect < 0.9f;
        EXPECT_FLOAT_EQ(a[i], expect) << "segment " << i << " of line " << seg.line_of(i);
    }
    EXPECT_GT(unseen, 12u) << "the parts off screen have segments without fragments";
    EXPECT_GE(took_neighbour, 13u) << "every line runs off screen once";
    EXPECT_GE(took_cleared, 1u) << "a curtain line clears right at the edge of the picture";
}
