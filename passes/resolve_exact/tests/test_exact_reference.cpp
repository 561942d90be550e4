// The exact transparency reference proven twice (issue 42): variant2_exact (the lists with every
// fragment, resolve_exact) and variant2_depth_peel (depth peeling) are two independent ways to
// the same picture, so each checks the other: on the phantom and on real data, over the
// covered pixels, at most 0.1 % more than 2/255 apart. And what makes them exact: ties by line
// id in both, every fragment however long the list (any sort block gives the same picture,
// resolve_list's 32-fragment cap does not), and memory or layers that run out fail by name.
#include "frame_capture.hpp"
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

void expect_agree(const Scene& scene, glm::ivec2 size, double t, const std::vector<std::string>& sets,
                  const std::string& what) {
    const Frame exact = render("variant2_exact", scene, size, t, sets);
    const Frame peel = render("variant2_depth_peel", scene, size, t, sets);
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
// different speeds (colours): both techniques put the lower line id in front, whichever colour
// it has. Checked against each line alone: with opacity a, line 0 over line 1 over white is
// p0 + (1 - a) (p1 - white), where p_i is line i alone over white.
TEST(ExactReference, TiesAreOrderedByLineIdInBoth) {
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
        const Image& im = render(g, straight_lines_scene(lines), {160, 90}, 5.0, sets, cam)["final"];
        return glm::vec3(im.at(x, y, 0), im.at(x, y, 1), im.at(x, y, 2));
    };
    const float a = 128.0f / 255.0f;  // 0.5 as the lists' 8 bits
    const glm::vec3 white(1.0f);
    for (const std::string g : {"variant2_exact", "variant2_depth_peel"}) {
        const glm::vec3 p_slow = centre(g, {slow}), p_fast = centre(g, {fast});
        ASSERT_GT(glm::length(p_slow - p_fast), 0.2f) << g << ": the two speeds should have different colours";
        const glm::vec3 slow_front = p_slow + (1.0f - a) * (p_fast - white);
        const glm::vec3 fast_front = p_fast + (1.0f - a) * (p_slow - white);
        ASSERT_GT(glm::length(slow_front - fast_front), 0.05f);
        for (bool slow_first : {true, false}) {
            const glm::vec3 got = slow_first ? centre(g, {slow, fast}) : centre(g, {fast, slow});
            const glm::vec3 want = slow_first ? slow_front : fast_front;
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(got[c], want[c], 2.5f / 255.0f) << g << (slow_first ? ": slow line 0" : ": fast line 0")
                                                             << ", channel " << c;
        }
    }
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
