// opacity_lists on real GL: the importance its lists carry, from a point array of the data and
// from a GLSL hook; a point array survives the importers' repair with its points; a missing
// array is an error that names the arrays there are.
#include "frame_runner.hpp"
#include "opacity_layout.hpp"
#include "straight_lines.hpp"

#include "io/pathline_io.hpp"

#include <pathlet/gpu_fence.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>

using namespace pathlet;
using namespace pathlet::oo_test;

namespace {

const std::string kGraph = std::string(PATHLET_SOURCE_DIR) + "/graphs/variant4_opacity.json";
const glm::ivec2 kSize{160, 120};

// Three parallel lines at the same speed, a "pressure" of 10, 30 and 20.
const Scene& three_lines() {
    static const Scene s = straight_lines_scene({{{0, 0, 0}, {10, 0, 0}, 5.0f, 41, {10.0f}},
                                                 {{0, 3, 0}, {10, 3, 0}, 5.0f, 41, {30.0f}},
                                                 {{0, 6, 0}, {10, 6, 0}, 5.0f, 41, {20.0f}}},
                                                {"pressure"});
    return s;
}

// Per line, the importance of every node of the lists.
std::map<uint32_t, std::vector<float>> node_importance(const std::vector<std::string>& sets) {
    FrameRunner run(kGraph, sets, three_lines(), kSize, camera_down_z(three_lines(), {5, 3, 0}, 30, 30, kSize),
                    {"oo_lists", "oo_segments"});
    run.frame(0.0);
    const std::vector<uint32_t> l = run.words("oo_lists");
    const Segments seg(run.words("oo_segments"));
    const uint32_t nodes_at = (8 + l.at(3) * l.at(4) + 3) & ~3u;
    std::map<uint32_t, std::vector<float>> out;
    for (uint32_t i = 0; i < std::min(l.at(6), l.at(5)); ++i)
        out[seg.line_of(l.at(nodes_at + 4 * i))].push_back(as_float(l.at(nodes_at + 4 * i + 2)));
    return out;
}

const std::vector<std::string> kBase = {"window=-1", "line_width=0.8", "segment_length=2", "importance_exponent=1"};

std::vector<std::string> with(std::vector<std::string> extra) {
    std::vector<std::string> s = kBase;
    s.insert(s.end(), extra.begin(), extra.end());
    return s;
}

}  // namespace

TEST(OpacityLists, ImportanceFromAPointArrayOnItsRange) {
    const auto g = node_importance(with({"importance=array", "importance_array=pressure",
                                         "opacity_lists.importance_min=10", "opacity_lists.importance_max=30"}));
    const float expect[3] = {0.0f, 1.0f, 0.5f};
    for (uint32_t line = 0; line < 3; ++line) {
        ASSERT_GT(g.count(line) ? g.at(line).size() : 0u, 20u) << "line " << line;
        for (float x : g.at(line)) ASSERT_NEAR(x, expect[line], 1e-6) << "line " << line;
    }
    // Speed, the default, is the same for all three lines.
    const auto speed = node_importance(with({"opacity_lists.importance_min=0", "opacity_lists.importance_max=10"}));
    for (uint32_t line = 0; line < 3; ++line)
        for (float x : speed.at(line)) ASSERT_NEAR(x, 0.5f, 1e-6);
}

// Variant 4 with importance=array takes any array `pathlet info` lists: the velocity the
// importers read as the lines' own (as its magnitude, whatever its case) and time too.
TEST(OpacityLists, ImportanceFromTheVelocityArrayIsTheSpeed) {
    static const Scene speeds = straight_lines_scene({{{0, 0, 0}, {10, 0, 0}, 2.0f, 41, {}},
                                                      {{0, 3, 0}, {10, 3, 0}, 6.0f, 41, {}},
                                                      {{0, 6, 0}, {10, 6, 0}, 4.0f, 41, {}}});
    auto importance = [&](const std::string& array) {
        FrameRunner run(kGraph, with({"importance=array", "importance_array=" + array, "opacity_lists.importance_min=2",
                                     "opacity_lists.importance_max=6"}),
                        speeds, kSize, camera_down_z(speeds, {5, 3, 0}, 30, 30, kSize), {"oo_lists", "oo_segments"});
        run.frame(0.0);
        const std::vector<uint32_t> l = run.words("oo_lists");
        const Segments seg(run.words("oo_segments"));
        const uint32_t nodes_at = (8 + l.at(3) * l.at(4) + 3) & ~3u;
        std::map<uint32_t, std::vector<float>> out;
        for (uint32_t i = 0; i < std::min(l.at(6), l.at(5)); ++i)
            out[seg.line_of(l.at(nodes_at + 4 * i))].push_back(as_float(l.at(nodes_at + 4 * i + 2)));
        return out;
    };
    for (const std::string name : {"velocity", "Velocity"}) {
        const auto g = importance(name);
        const float expect[3] = {0.0f, 1.0f, 0.5f};
        for (uint32_t line = 0; line < 3; ++line) {
            ASSERT_GT(g.count(line) ? g.at(line).size() : 0u, 20u) << name << ", line " << line;
            for (float x : g.at(line)) ASSERT_NEAR(x, expect[line], 1e-5) << name << ", line " << line;
        }
    }
    // Time runs from 0 to 10 / speed along each line: 5 s on line 0 (importance up to 0.75),
    // 1.7 s on line 1 (below the range: 0 throughout).
    const auto t = importance("time");
    ASSERT_GT(t.count(0) ? t.at(0).size() : 0u, 20u);
    EXPECT_EQ(*std::min_element(t.at(0).begin(), t.at(0).end()), 0.0f) << "t <= 2 s on line 0";
    EXPECT_GT(*std::max_element(t.at(0).begin(), t.at(0).end()), 0.6f) << "t up to 5 s on line 0";
    ASSERT_GT(t.count(1) ? t.at(1).size() : 0u, 20u);
    EXPECT_EQ(*std::max_element(t.at(1).begin(), t.at(1).end()), 0.0f) << "t <= 1.7 s on line 1";
}

TEST(OpacityLists, ImportanceFromAHookOfLinePoint) {
    // importance_near.glsl: 1 at the point, falling to 0 at focus_radius; the middle line passes
    // through the point, the others lie 3 away, beyond the radius.
    const auto g = node_importance(with({"importance=hook", "opacity_lists.color_hook=importance_near.glsl",
                                         "opacity_lists.focus_center=[5,3,0]", "opacity_lists.focus_radius=2.5"}));
    ASSERT_EQ(g.size(), 3u) << "every fragment is a node, important or not";
    for (uint32_t line : {0u, 2u})
        for (float x : g.at(line)) ASSERT_EQ(x, 0.0f) << "line " << line;
    const std::vector<float>& mid = g.at(1);
    EXPECT_GT(*std::max_element(mid.begin(), mid.end()), 0.9f);
    EXPECT_EQ(*std::min_element(mid.begin(), mid.end()), 0.0f) << "the line runs on beyond the radius";
}

TEST(OpacityLists, AMissingArrayNamesTheArraysThereAre) {
    try {
        node_importance(with({"importance=array", "importance_array=vorticity"}));
        FAIL() << "no error";
    } catch (const std::exception& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("vorticity"), std::string::npos) << msg;
        EXPECT_NE(msg.find("pressure"), std::string::npos) << msg;
        EXPECT_NE(msg.find("velocity (as its magnitude), time"), std::string::npos) << msg;
        EXPECT_NE(msg.find("opacity_lists"), std::string::npos) << msg;
    }
}

TEST(OpacityLists, APointArrayTravelsWithItsPointsThroughRepair) {
    // Line 0 repeats its second point (dropped by the repair) and runs backwards in time (reversed).
    const std::string path = test_scratch_dir("pathlet_oo_lists") + "/arrays.vtk";
    std::ofstream(path) << "# vtk DataFile Version 4.2\nt\nASCII\nDATASET POLYDATA\nPOINTS 6 float\n"
                           "0 0 0 1 0 0 1 0 0 2 0 0 0 1 0 1 1 0\nLINES 2 8\n4 0 1 2 3\n2 4 5\n"
                           "POINT_DATA 6\nSCALARS time float\nLOOKUP_TABLE default\n3 2 2 1 0 1\n"
                           "SCALARS pressure float\nLOOKUP_TABLE default\n10 11 11 12 20 21\n"
                           "VECTORS vorticity float\n3 4 0 0 0 1 0 0 1 0 0 2 1 0 0 0 1 0\n";
    io::LoadReport report;
    const Pathlines pl = io::load_pathlines(path, {}, &report);
    ASSERT_EQ(pl.point_count(), 5u);
    const PointArray* p = pl.array("pressure");
    const PointArray* v = pl.array("vorticity");
    ASSERT_TRUE(p && v);
    EXPECT_EQ(pl.array("time"), nullptr) << "time is the pathlines' own";
    EXPECT_EQ(p->values, (std::vector<float>{12, 11, 10, 20, 21}));  // reversed, the duplicate gone
    EXPECT_EQ(v->values, (std::vector<float>{2, 1, 5, 1, 1}));      // vectors as their magnitude
    pl.check_consistent("test");
}

// The lists learn an overflow from an earlier frame's count, read without waiting, and grow. The
// GPU's latency is simulated (pathlet/gpu_fence.hpp: K frames, the environment's when it is 2 or
// more, else 3) and nothing is read back between the frames, so the counts really are late: a
// count read only once its fence may have signalled must still reach the pass (before 9690640 the
// pass replaced its fence with the next frame's before it signalled, and never grew), and every
// frame that overflowed is reported incomplete.
TEST(OpacityLists, AnOverflowFoundFramesLateGrowsTheListsUntilEveryFragmentFits) {
    set_simulated_gpu_latency(-1);
    const int k = simulated_gpu_latency() >= 2 ? simulated_gpu_latency() : 3;
    set_simulated_gpu_latency(k);
    struct Restore {
        ~Restore() { set_simulated_gpu_latency(-1); }
    } restore;
    FrameRunner run(kGraph, with({"opacity_lists.nodes_per_pixel=0.01"}), three_lines(), kSize,
                    camera_down_z(three_lines(), {5, 3, 0}, 30, 30, kSize), {"oo_lists"});
    for (int f = 0; f < 3 * k; ++f) run.frame(0.0);  // the same picture, never read back in between
    const std::vector<uint32_t> l = run.words("oo_lists");
    const std::set<uint64_t>& incomplete = run.executor().incomplete_frames();
    EXPECT_TRUE(incomplete.count(0)) << "the first frame overflows (0.01 nodes a pixel), or the test says nothing";
    EXPECT_LE(incomplete.size(), size_t(2 * k)) << "a count arrives at most 2K - 1 frames late";
    EXPECT_FALSE(incomplete.count(uint64_t(3 * k - 1))) << "the last frame fits";
    EXPECT_GE(l.at(5), l.at(6)) << "grown to hold every fragment (K = " << k << ")";
}
