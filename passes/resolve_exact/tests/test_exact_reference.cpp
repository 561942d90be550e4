// The exact transparency reference proven twice: variant2_exact (the lists with every fragment,
// resolve_exact) and variant2_depth_peel (depth peeling) are two independent ways to the same
// picture, so each checks the other: on the phantom and on real data, over the covered pixels,
// at most 0.1 % more than 2/255 apart. Also where the depth ties (one rule in both,
// shaders/oit_depth_group.glsl: fragments at one depth are one layer): halos pushed past the far
// plane, lines crossing the near plane, twins of one depth; and what makes them exact: every
// fragment however long the list (any sort block gives the same picture), a cut walk reported,
// memory or layers that run out fail by name.
#include "cycle_list.hpp"
#include "frame_capture.hpp"
#include "oit_lists.hpp"
#include "straight_lines.hpp"

#include "executor.hpp"
#include "io/pathline_io.hpp"
#include "phantom/phantom.hpp"
#include "trace/field_readers.hpp"
#include "trace/marching_cubes.hpp"
#include "trace/tracer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

using namespace pathlet;

namespace {

const std::string kSrc = PATHLET_SOURCE_DIR;

std::string graph(const std::string& name) { return kSrc + "/graphs/" + name + ".json"; }

// resolve_exact's statistics arrive without a wait, a frame late: graphs with it render twice.
Frame render(const std::string& name, const Scene& scene, glm::ivec2 size, double t, std::vector<std::string> sets,
             const std::string& camera = "") {
    RenderOptions opt;
    opt.camera_path = camera;
    opt.repeat = name == "variant2_exact" ? 2 : 1;
    opt.graph_path = graph(name);
    opt.size = size;
    opt.time.start = t;
    opt.sets = std::move(sets);
    opt.sets.push_back("overlay=false");
    return render_frame(test_runtime(), scene, opt, {"oit_color", "final", "coverage"});
}

struct Agreement {
    size_t covered = 0, apart = 0;  // pixels either covers; of them more than 2/255 apart
    float max_diff = 0;
    double share() const { return covered ? double(apart) / double(covered) : 1.0; }
};

Agreement compare(const Frame& a, const Frame& b, const std::string& image = "final") {
    const Image &ia = a[image], &ib = b[image], &ca = a["coverage"], &cb = b["coverage"];
    Agreement r;
    for (int y = 0; y < ia.height; ++y)
        for (int x = 0; x < ia.width; ++x) {
            if (ca.at(x, y, 0) >= 1.0f && cb.at(x, y, 0) >= 1.0f) continue;
            ++r.covered;
            float d = 0;
            for (int c = 0; c < 3; ++c) d = std::max(d, std::fabs(ia.at(x, y, c) - ib.at(x, y, c)));
            r.apart += d > 2.0f / 255.0f + 1e-6f;
            r.max_diff = std::max(r.max_diff, d);
        }
    return r;
}

// `exact_sets` and `peel_sets` go to one graph each (a pass parameter names its own pass).
void expect_agree(const Scene& scene, glm::ivec2 size, double t, const std::vector<std::string>& sets,
                  const std::string& what, const std::string& camera = "", std::vector<std::string> exact_sets = {},
                  std::vector<std::string> peel_sets = {}) {
    exact_sets.insert(exact_sets.begin(), sets.begin(), sets.end());
    peel_sets.insert(peel_sets.begin(), sets.begin(), sets.end());
    const Frame exact = render("variant2_exact", scene, size, t, exact_sets, camera);
    const Frame peel = render("variant2_depth_peel", scene, size, t, peel_sets, camera);
    const Agreement a = compare(exact, peel);
    std::printf("%s: %zu covered px, %zu (%.4f %%) more than 2/255 apart, max %.1f/255; %g layers peeled, "
                "truncated %g\n",
                what.c_str(), a.covered, a.apart, 100.0 * a.share(), 255.0 * a.max_diff, peel.stats.at("layers"),
                exact.stats.at("truncated_pixels"));
    EXPECT_GT(a.covered, size_t(size.x) * size_t(size.y) / 50) << what << ": the lines cover almost nothing";
    EXPECT_LE(a.share(), 0.001) << what;
    EXPECT_EQ(exact.stats.at("truncated_pixels"), 0.0) << what;
    EXPECT_EQ(exact.stats.at("dropped_fragments"), 0.0) << what;
    EXPECT_GT(peel.stats.at("layers"), 1.0) << what;
}

const Scene& study_phantom() {
    static const Scene s = phantom::make_phantom(phantom::phantom_preset("study"), {});
    return s;
}

}  // namespace

TEST(ExactReference, AgreesWithDepthPeelingOnTheStudyPhantom) {
    expect_agree(study_phantom(), {1280, 720}, 9.0, {}, "phantom, 1 s window");
}

// Whole lines peel 70 layers of 234k segments (75 s a frame at 1280x720 on llvmpipe): a
// quarter of the pixels here; `pathlet quality variant2_exact --reference variant2_depth_peel
// --set window=0 --size 1280x720` checks the full size (docs/transparency.md).
TEST(ExactReference, AgreesWithDepthPeelingOnThePhantomWithEveryLineWhole) {
    expect_agree(study_phantom(), {640, 360}, 9.0, {"window=0"}, "phantom, whole lines");
}

// Real data not made by this project (../shared/data/real), skipped where absent.
TEST(ExactReference, AgreesWithDepthPeelingOnRealData) {
    const char* env = std::getenv("PATHLET_REAL_DATA_DIR");
    const std::string dir = env && *env ? env : "";
    const std::string path = dir + "/aneurysm-pathlines/blood_flow";
    if (dir.empty() || !std::filesystem::exists(path))
        GTEST_SKIP() << "real data absent: " << (dir.empty() ? std::string("PATHLET_REAL_DATA_DIR unset") : path);
    Scene s;
    s.lines = io::load_pathlines(path, {});
    s.source = path;
    const double t = 0.5 * (double(s.lines.time_min()) + double(s.lines.time_max()));
    expect_agree(s, {1280, 720}, t, {}, "aneurysm, 1 s window");
    expect_agree(s, {640, 360}, t, {"window=0"}, "aneurysm, whole lines");
    // The CFD aortic arch (4DFlowNet), traced as `pathlet trace` does by default, with its wall.
    const std::string arch = dir + "/aortic-arch-cfd-4dflownet/example_data_HR.h5";
    if (!std::filesystem::exists(arch)) GTEST_SKIP() << "real data absent: " << arch;
    const trace::VelocityField field = trace::load_velocity_field(arch);
    trace::TraceOptions o;
    o.time_end = 10.0f;
    o.threads = 2;
    Scene a;
    a.lines = trace::trace_pathlines(field, o);
    a.mesh = trace::vessel_wall(field);
    a.source = arch;
    expect_agree(a, {1280, 720}, 5.0, {}, "aortic arch (CFD), 1 s window");
    // Every line whole: 50 layers peeled at t = 5 s (about 7 s on llvmpipe, mostly the geometry
    // drawn once a layer); a quarter of the pixels, as for the aneurysm.
    expect_agree(a, {640, 360}, 5.0, {"window=0"}, "aortic arch (CFD), whole lines");
}

// Two lines with the same points (so every fragment of one has a twin at the same depth) and
// different speeds (colours): one layer of both in either reference, whichever line comes
// first, with the opacity of two (1 - (1 - a)^2) and the mean of the two colours (equal
// absorbances), checked against each line alone: line i alone over white is p_i = a c_i +
// (1 - a) white.
TEST(ExactReference, FragmentsAtOneDepthAreOneLayerWhateverTheirLinesInBoth) {
    const StraightLine slow{.from = {0, 0, 0}, .to = {10, 0, 0}, .speed = 1.0f};
    StraightLine fast = slow;
    fast.speed = 3.0f;
    // One opacity (0.5, uniform_fade's default) everywhere, through the graph variable color_hook.
    const std::vector<std::string> sets = {"window=0", "color_hook=uniform_fade.glsl", "tail_fade=0", "head_fade=0",
                                           "lod=0", "speed_min=1", "speed_max=3", "line_width=1", "colormap=coolwarm"};
    const std::string cam = write_camera_down_z(test_scratch_dir("pathlet_exact") + "/cam.json", {5, 0, 0}, 30, 30);
    // The pixel: the darkest of the middle column with the slow line alone (on its axis).
    const Image lone = render("variant2_exact", straight_lines_scene({slow}), {160, 90}, 5.0, sets, cam)["final"];
    const int x = lone.width / 2;
    int y = 0;
    for (int r = 0; r < lone.height; ++r)
        if (lone.at(x, r, 1) + lone.at(x, r, 0) < lone.at(x, y, 1) + lone.at(x, y, 0)) y = r;
    auto centre = [&](const std::string& g, const std::vector<StraightLine>& lines) {
        const Image im = render(g, straight_lines_scene(lines), {160, 90}, 5.0, sets, cam)["final"];
        return glm::vec3(im.at(x, y, 0), im.at(x, y, 1), im.at(x, y, 2));
    };
    const float a = 128.0f / 255.0f;  // 0.5 as the lists' 8 bits
    const glm::vec3 white(1.0f);
    for (const std::string g : {"variant2_exact", "variant2_depth_peel"}) {
        const glm::vec3 p_slow = centre(g, {slow}), p_fast = centre(g, {fast});
        ASSERT_GT(glm::length(p_slow - p_fast), 0.2f) << g << ": the two speeds should have different colours";
        const glm::vec3 c_slow = (p_slow - (1.0f - a) * white) / a, c_fast = (p_fast - (1.0f - a) * white) / a;
        const float both = 1.0f - (1.0f - a) * (1.0f - a);
        const glm::vec3 want = both * 0.5f * (c_slow + c_fast) + (1.0f - both) * white;
        // Either order in front would be this far from it: the rule is not an order.
        ASSERT_GT(glm::length(want - (p_slow + (1.0f - a) * (p_fast - white))), 0.03f);
        for (bool slow_first : {true, false}) {
            const glm::vec3 got = slow_first ? centre(g, {slow, fast}) : centre(g, {fast, slow});
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(got[c], want[c], 2.5f / 255.0f) << g << (slow_first ? ": slow line 0" : ": fast line 0")
                                                            << ", channel " << c;
        }
    }
}

// Where the references' rule bites: ties at clamped depths. The lists are read back to show that
// each scene has them (pixels with fragments at exactly 1.0 or 0.0, and pixels where one line
// has several fragments at one depth), and the two references must still agree per pixel.
struct Ties {
    size_t covered = 0, at_far = 0, at_near = 0, one_line_repeated = 0;
};

Ties ties_in_lists(const Scene& scene, glm::ivec2 size, double t, const std::vector<std::string>& sets,
                   const std::string& camera = "") {
    RenderOptions opt;
    opt.camera_path = camera;
    opt.graph_path = graph("variant2_exact");
    opt.size = size;
    opt.time.start = t;
    opt.sets = sets;
    opt.sets.push_back("overlay=false");
    opt.keep = {"heads", "nodes"};
    Ties ties;
    opt.time.end = t;
    opt.warmup = 0;
    opt.write_images = false;
    opt.quiet = true;
    render(test_runtime(), scene, opt, [&](const Executor& ex, size_t) {
        const OitLists l = read_oit_lists(ex);
        for (GLuint h : l.heads) {
            if (h == 0xFFFFFFFFu) continue;
            ++ties.covered;
            std::vector<std::pair<double, GLuint>> frags;  // depth, line id
            for (GLuint i = h; i != 0xFFFFFFFFu; i = l.nodes[i].z) frags.emplace_back(node_depth(l.nodes[i]), l.nodes[i].w);
            std::sort(frags.begin(), frags.end());
            bool far = false, near = false, repeated = false;
            for (size_t k = 0; k < frags.size(); ++k) {
                far = far || frags[k].first == 1.0;
                near = near || frags[k].first == 0.0;
                repeated = repeated || (k > 0 && frags[k] == frags[k - 1]);
            }
            ties.at_far += far, ties.at_near += near, ties.one_line_repeated += repeated;
        }
    });
    std::printf("lists: %zu covered px, %zu with a fragment at 1.0, %zu at 0.0, %zu where one line has two at one "
                "depth\n",
                ties.covered, ties.at_far, ties.at_near, ties.one_line_repeated);
    return ties;
}

// halo_depth 1: every halo fragment is pushed back by up to the whole depth range, most of them
// past the far plane, where the linear depth is clamped to exactly 1.0. Depth peeling peeled
// with LESS against its cleared 1.0 and lost them all (35.6 % of the covered pixels more than
// 2/255 apart with the 1 s window). Halos at least a pixel wide (halo_min_px 1), so that many
// pixels hold them.
TEST(ExactReference, AgreesWithHalosPushedPastTheFarPlane) {
    const Scene& s = study_phantom();
    for (const std::string window : {"window=1", "window=0"}) {
        const Ties ties = ties_in_lists(s, {640, 360}, 9.0, {window, "fill_list.halo_depth=1", "fill_list.halo_min_px=1"});
        EXPECT_GT(ties.at_far, ties.covered / 3) << window << ": the halos should reach the far plane";
        EXPECT_GT(ties.one_line_repeated, 50u) << window << ": pixels where one line has two fragments at 1.0";
        expect_agree(s, {640, 360}, 9.0, {window}, "phantom, halos past the far plane, " + window, "",
                     {"fill_list.halo_depth=1", "fill_list.halo_min_px=1"},
                     {"depth_peel.halo_depth=1", "depth_peel.halo_min_px=1"});
    }
}

// Lines that run through the near plane towards the camera (the camera inside the data): the
// tube's bulge in front of the near plane clamps their linear depth to exactly 0.0, many
// fragments of one line at one depth in every pixel near the plane.
TEST(ExactReference, AgreesWhereLinesCrossTheNearPlane) {
    // The camera at z = 20 looks down -z; the data's bounding sphere holds it, so the near plane
    // is 1 % of the sphere's radius (about 0.22) in front of it. Lines converge on the eye and end
    // 0.15 to 0.38 in front of it, just off the axis: their last segments fill the picture, and
    // the tube's bulge (half a width, 0.11) takes their fragments in front of the near plane.
    // Their last points zigzag by less than the width, so a line's segments overlap there.
    std::vector<StraightLine> lines;
    for (int i = 0; i < 24; ++i) {
        const float a = 0.2618f * float(i), r = 0.01f * float(1 + i % 4);
        lines.push_back({.from = {6.0f * std::cos(a), 6.0f * std::sin(a), -20.0f},
                         .to = {r * std::cos(a), r * std::sin(a), 20.0f - (0.15f + 0.01f * float(i))},
                         .speed = 1.0f + 0.25f * float(i % 8)});
    }
    Scene scene = straight_lines_scene(lines);
    for (const LineRange& l : scene.lines.lines)
        for (uint32_t k = l.count - 8; k < l.count; ++k) scene.lines.position[l.first + k].x += (k % 2 ? 0.03f : -0.03f);
    const std::string cam = write_camera_down_z(test_scratch_dir("pathlet_exact") + "/near_cam.json", {0, 0, 0}, 20, 40);
    const std::vector<std::string> sets = {"window=0", "color_hook=uniform_fade.glsl", "tail_fade=0", "head_fade=0",
                                           "lod=0"};
    std::vector<std::string> lists = sets;
    lists.push_back("fill_list.opacity=0.3");
    const Ties ties = ties_in_lists(scene, {320, 180}, 5.0, lists, cam);
    EXPECT_GT(ties.at_near, ties.covered / 20) << "fragments in front of the near plane should be clamped to 0";
    EXPECT_GT(ties.one_line_repeated, ties.covered / 100) << "one line should have several fragments at depth 0";
    expect_agree(scene, {320, 180}, 5.0, sets, "lines through the near plane", cam, {"fill_list.opacity=0.3"},
                 {"depth_peel.opacity=0.3"});
}

// Lists far longer than resolve_list's cap and than the sort block: every fragment counts, so
// the block size changes nothing, down to one fragment a round (253 rounds of a 253-fragment
// list: more than one draw's budget of node visits, so the pixels carry their state to the next
// draw instead of running a loop long enough for a driver to cut; llvmpipe cut such pixels
// silently when it was one loop). On the study phantom, whole lines at opacity 0.05.
TEST(ExactReference, EveryFragmentWhateverTheSortBlock) {
    const Scene& s = study_phantom();
    const std::vector<std::string> base = {"window=0", "color_hook=uniform_fade.glsl", "fill_list.opacity=0.05"};
    auto with = [&](std::string block) {
        std::vector<std::string> v = base;
        v.push_back("sort_block=" + block);
        return render("variant2_exact", s, {320, 180}, 9.0, v);
    };
    const Frame b16 = with("16"), b4 = with("4"), b64 = with("64"), b1 = with("1");
    // Stats are means over the two frames, and the first sees no count yet (read without a wait).
    ASSERT_GT(2 * b16.stats.at("peak_nodes_per_pixel"), 64.0) << "the lists should be longer than 64 fragments";
    EXPECT_EQ(b16.stats.at("draws"), 1.0);
    EXPECT_GT(b1.stats.at("draws"), 2.0) << "one fragment a round should need more than one draw's budget";
    for (const Frame* f : {&b16, &b4, &b64, &b1}) {
        EXPECT_EQ(f->stats.at("truncated_pixels"), 0.0);
        const Agreement a = compare(b16, *f);
        EXPECT_EQ(a.apart, 0u) << "max " << 255.0f * a.max_diff << "/255";
        EXPECT_EQ(a.max_diff, 0.0f);
    }
    // Draws that run out fail by name.
    try {
        std::vector<std::string> v = base;
        v.insert(v.end(), {"sort_block=1", "resolve.max_draws=2"});
        render("variant2_exact", s, {320, 180}, 9.0, v);
        FAIL() << "resolved with too few draws";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("max_draws"), std::string::npos) << e.what();
    }
}

// Memory runs out: a clear error naming max_memory_mb, no picture with fragments missing.
TEST(ExactReference, NodeMemoryThatRunsOutFailsByName) {
    try {
        render("variant2_exact", study_phantom(), {320, 180}, 9.0, {"max_memory_mb=0.05"});
        FAIL() << "rendered with too little node memory";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("max_memory_mb"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("never_drop"), std::string::npos) << e.what();
    }
}

// Layers run out: depth peeling fails naming max_layers rather than cut the frame short.
TEST(ExactReference, LayersThatRunOutFailByName) {
    try {
        render("variant2_depth_peel", study_phantom(), {320, 180}, 9.0, {"max_layers=2"});
        FAIL() << "peeled with too few layers";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("max_layers"), std::string::npos) << e.what();
    }
}

// A walk cut short is never silent: a cyclic list in one frame of three (the list holding node 0
// links to itself in frame 1) makes that frame, and only it, incomplete, though the frame after
// it is clean (the cut count is the frame's own, read with the pending count).
TEST(ExactReference, ACyclicListInOneFrameMakesThatFrameIncomplete) {
    add_cycle_list_pass(test_runtime());
    RenderOptions opt;
    opt.graph_path = write_cyclic_list_graph(test_scratch_dir("pathlet_exact") + "/cyclic.json", 1);
    opt.size = {160, 90};
    opt.time = {2.0, 2.08, 0.04};
    opt.warmup = 0;
    opt.write_images = false;
    opt.quiet = true;
    opt.sets = {"overlay=false"};
    const RenderResult r = render(test_runtime(), small_phantom_scene(), opt);
    EXPECT_EQ(r.frames, 3u);
    EXPECT_EQ(incomplete_frames_line(r), "incomplete frames: 1 of 3 (1)");
    double cut = 0;  // the mean over the three frames
    for (const auto& p : r.profiler.passes())
        if (p.name == "resolve") cut = p.stats.at("truncated_pixels");
    EXPECT_GT(cut, 0.0) << "the cut pixel is counted";
}
