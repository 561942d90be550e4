// pathlet quality --transparency on scenes where the answer is known: one pixel composited by
// hand; a fast line behind a curtain of slow ones, hidden by variant 2's opaque lines (and by
// opacity optimization with q = 0), visible with q > 0; a frozen view that stays still; a graph
// without OIT is not measured.
#include "transparency.hpp"

#include "frame_capture.hpp"
#include "straight_lines.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>

#include <sys/wait.h>

using namespace pathlet;
using namespace pathlet::quality;

namespace {

const std::string kSrc = PATHLET_SOURCE_DIR;

// 14 slow lines (speed 10) side by side, overlapping, in front of one fast line (speed 100)
// along the same stretch. The measures' camera looks along the thinnest axis (z) from -z.
const Scene& curtain() {
    static const Scene s = [] {
        std::vector<StraightLine> l;
        for (int k = 0; k < 14; ++k) l.push_back({{0, 0.4f * k, -3}, {20, 0.4f * k, -3}, 10.0f, 81});
        l.push_back({{0, 2.6f, 0}, {20, 2.6f, 0}, 100.0f, 161});
        return straight_lines_scene(l);
    }();
    return s;
}

TransparencyResult measure(const std::string& graph, std::vector<std::string> sets, const Scene& scene,
                           const std::string& time = "0:0.08:0.04", int repeat = 1) {
    TransparencyOptions o;
    o.graph_path = kSrc + "/graphs/" + graph + ".json";
    o.sets = std::move(sets);
    o.size = {320, 180};
    o.time = parse_time_range(time);
    o.repeat = repeat;
    return measure_transparency(test_runtime(), scene, o);
}

const std::vector<std::string> kCurtain = {"window=-1", "tail_fade=0", "head_fade=0", "line_width=0.6"};

std::vector<std::string> v4(double q) {
    std::vector<std::string> s = kCurtain;
    for (const char* x : {"opacity_lists.importance_min=0", "opacity_lists.importance_max=100", "importance_exponent=1",
                          "r=0", "lambda=1", "adapt=fixed"})
        s.push_back(x);
    s.push_back("q=" + std::to_string(q));
    return s;
}

}  // namespace

TEST(Transparency, OnePixelCompositedFrontToBack) {
    SegmentSums sums(8);
    std::vector<Fragment> f = {{0.3f, 2, 0, 1.0f, 5}, {0.1f, 1, 0, 0.5f, 3}, {0.2f, 1, 0, 0.5f, 4}};
    EXPECT_DOUBLE_EQ(composite_pixel(f, 32, sums), 1.0);
    EXPECT_DOUBLE_EQ(sums.ink[3], 0.5);
    EXPECT_DOUBLE_EQ(sums.ink[4], 0.25);
    EXPECT_DOUBLE_EQ(sums.ink[5], 0.25);
    EXPECT_DOUBLE_EQ(sums.unoccluded[5], 0.25);
    EXPECT_EQ(sums.seen, (std::vector<uint32_t>{3, 4, 5}));
    sums.clear();
    f.push_back({0.05f, 0, 0, 0.5f, 6});  // nearer than all: the last is beyond the two kept
    EXPECT_DOUBLE_EQ(composite_pixel(f, 2, sums), 0.75);
    EXPECT_EQ(sums.footprint[5], 0u);
    EXPECT_DOUBLE_EQ(sums.unoccluded[3], 0.5);
}

TEST(Transparency, AnImportantLineBehindACurtainBecomesVisibleOnlyWithQ) {
    const TransparencyResult v2 = measure("variant2_oit", kCurtain, curtain());
    const TransparencyResult off = measure("variant4_opacity", v4(0.0), curtain());
    const TransparencyResult on = measure("variant4_opacity", v4(60.0), curtain());
    for (const TransparencyResult* r : {&v2, &off, &on}) {
        ASSERT_TRUE(r->not_measured.empty()) << r->not_measured;
        EXPECT_EQ(r->frames, 3u);
        EXPECT_GT(r->located, 0.99 * double(r->fragments)) << r->graph << ": fragments placed on their line";
        EXPECT_GT(r->focus_footprint, 500u);
        EXPECT_EQ(r->overflow, 0u);
        // Each fragment on its own data segment: most of the curtain's 14 x 80 segments, every frame.
        EXPECT_GT(r->context_seen, 3u * 14 * 60) << r->graph;
    }
    EXPECT_DOUBLE_EQ(on.focus_speed, 100.0) << "focus: the fast line, the top 10 % of segments";
    EXPECT_LT(v2.focus_visibility, 0.05) << "variant 2: behind opaque lines";
    EXPECT_LT(off.focus_visibility, 0.05) << "q = 0: nothing asks the curtain to clear";
    EXPECT_LT(off.focus_unoccluded, 0.05);
    EXPECT_GT(on.focus_visibility, 0.5);
    EXPECT_GT(on.focus_unoccluded, 0.7);
    EXPECT_GT(on.focus_ink_share, 5 * off.focus_ink_share + 0.1);
    // The price: the two curtain lines right in front of it (of 14) fade below the threshold.
    EXPECT_GT(off.context_coverage, 0.95);
    EXPECT_LT(on.context_coverage, off.context_coverage - 0.1);
    EXPECT_GT(on.context_coverage, 0.75) << "the rest of the curtain stays";
    EXPECT_LT(on.pixel_coverage, off.pixel_coverage);
    // Whole lines, a still camera: nothing changes between frames.
    EXPECT_LT(off.alpha_change_max, 1e-6);
    EXPECT_LT(on.alpha_change_max, 1e-4);
}

TEST(Transparency, AFrozenViewOfThePhantomConvergesAndStaysStill) {
    const Scene& s = small_phantom_scene();
    const TransparencyResult r = measure("variant4_opacity", {}, s, "2", 60);
    ASSERT_EQ(r.max_alpha_change_per_frame.size(), 59u);
    EXPECT_LT(r.max_alpha_change_per_frame.back(), 1e-4);
    EXPECT_GT(r.fragments, 10000u);
}

// The alpha change bounded below too (a measure that always said 0 passes every bound above):
// the phantom's pathlets move on, so each frame's opacities differ from the last's.
TEST(Transparency, AnAnimatedViewChangesItsOpacitiesEveryFrame) {
    const TransparencyResult r = measure("variant4_opacity", {}, small_phantom_scene(), "2:2.2");
    ASSERT_EQ(r.frames, 6u);
    ASSERT_EQ(r.max_alpha_change_per_frame.size(), 5u);
    for (double d : r.max_alpha_change_per_frame) EXPECT_GT(d, 1e-2) << "a frame whose opacities did not change";
    EXPECT_GT(r.alpha_change_mean, 1e-3);
    EXPECT_GE(r.alpha_change_p95, r.alpha_change_mean) << "a few segments change much, most little";
    EXPECT_DOUBLE_EQ(r.alpha_change_max, *std::max_element(r.max_alpha_change_per_frame.begin(), r.max_alpha_change_per_frame.end()))
        << "the run's largest change is its largest frame's";
    EXPECT_LE(r.alpha_change_max, 1.0);
}

TEST(Transparency, AGraphWithoutOitIsNotMeasured) {
    const TransparencyResult r = measure("variant1_lineao", {}, curtain());
    EXPECT_NE(r.not_measured.find("resolve_list"), std::string::npos) << r.not_measured;
}

TEST(Transparency, FewerThanTwoFramesIsAnError) {
    TransparencyOptions o;
    o.graph_path = kSrc + "/graphs/variant2_oit.json";
    o.time = parse_time_range("1");
    EXPECT_THROW(check_transparency_options(o), std::invalid_argument);
    o.repeat = 2;
    EXPECT_NO_THROW(check_transparency_options(o));
    o.focus_share = 1.5;
    EXPECT_THROW(check_transparency_options(o), std::invalid_argument);
}

TEST(Transparency, TheCommandRefusesAnExperimentWithoutTransparencyAndNamesABadFile) {
    const std::string dir = test_scratch_dir("pathlet_transparency");
    const std::string log = dir + "/out.txt";
    auto exit_code = [&](const std::string& args) {
        const int status = std::system((std::string(PATHLET_CLI) + " quality " + args + " > " + log + " 2>&1").c_str());
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    };
    auto output = [&] {
        std::ifstream in(log);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    EXPECT_EQ(exit_code("--experiment " + kSrc + "/graphs/experiments/transparency.json"), 2) << output();
    EXPECT_NE(output().find("--transparency"), std::string::npos) << output();
    const std::string bad = dir + "/bad.json";
    std::ofstream(bad) << R"({"graphs": [{"graph": "no_such_graph"}]})";
    EXPECT_NE(exit_code("--transparency --experiment " + bad), 0);
    EXPECT_NE(output().find("bad.json"), std::string::npos) << output();
    EXPECT_NE(output().find("no_such_graph"), std::string::npos) << output();
}
