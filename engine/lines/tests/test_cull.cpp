// The line kit's culling (lines::Drawer, chunk_culler.hpp): chunks hidden behind the lines in
// front or outside the view are not drawn, and the picture is what it was: the same pixels,
// at rest and while the camera orbits and the window moves (two-phase culling catches what
// the previous frame's visibility missed). OIT (depth ALWAYS) is frustum-culled only.
#include "frame_capture.hpp"
#include "executor.hpp"
#include "phantom/phantom.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

using namespace pathlet;

namespace {

// With the kit_probe fixture (ThePassKeepsItsOwnBindings); the first call makes the runtime.
Runtime& rt() { return test_runtime({PATHLET_TEST_PLUGIN_DIR}); }
const std::string kGraphs = std::string(PATHLET_SOURCE_DIR) + "/graphs/";

// Eight layers of 41 parallel lines, each layer a closed sheet at the width the test draws
// (0.3, lines 0.1 apart) facing the camera (the default framing looks along the thinnest
// extent, z, from its negative side): the front layer (z = -1.4) is larger than the others
// and hides them.
const Scene& layered_sheets() {
    static const Scene scene = [] {
        Scene s;
        for (int layer = 0; layer < 8; ++layer)
            for (int row = 0; row <= 40; ++row) {
                s.lines.lines.push_back({uint32_t(s.lines.position.size()), 101});
                const bool front = layer == 7;
                for (int k = 0; k <= 100; ++k) {
                    const float t = 0.1f * float(k), x = front ? 1.2f * t - 1.0f : t;
                    const float y = front ? 0.12f * float(row) - 0.4f : 0.1f * float(row) + 0.02f * float(layer);
                    s.lines.position.push_back({x, y, -0.2f * float(layer)});
                    s.lines.time.push_back(t);
                    s.lines.velocity.push_back({1.0f, 0.0f, 0.0f});
                }
            }
        s.source = "8 layered sheets of lines";
        return s;
    }();
    return scene;
}

struct CullRun {
    std::vector<Image> frames;
    double occluded = 0, phase1 = 0, phase2 = 0, frustum = 0, segments = 0;
};

// What a run renders besides the graph: the scene, the frames, the camera, more --sets.
struct RunSpec {
    const Scene* scene = nullptr;  // layered_sheets() when null
    double t0 = 4, t1 = 5, orbit = 0, window = 2.0;
    int min_segments = 0;          // the pass's cull_min_segments (0: cull at any size)
    std::vector<std::string> sets = {};
    std::string camera = {};       // a keyframed camera file; "" frames the data
};

// The culler's counts arrive through fenced copies, asked for before the frame's own copy (no
// mid-pass flush): a frame's stats are an earlier frame's counts, on llvmpipe the one before. So
// every run starts with one warm-up frame at t0, whose counts the first measured frame reports;
// a test that compares counts frame by frame renders one time (t0 = t1).

// Every frame of `graph` over [t0, t1], with the line pass's culling on or off.
CullRun render_run(const std::string& graph, const std::string& pass, bool cull, const std::string& resource,
                   const RunSpec& spec) {
    RenderOptions o;
    o.graph_path = graph.find('/') == std::string::npos ? kGraphs + graph : graph;
    o.size = {192, 128};
    o.sets = {pass + ".cull=" + std::string(cull ? "true" : "false"),
              pass + ".cull_min_segments=" + std::to_string(spec.min_segments), "overlay=false",
              "window=" + std::to_string(spec.window)};
    if (!spec.scene) o.sets.push_back("line_width=0.3");
    o.sets.insert(o.sets.end(), spec.sets.begin(), spec.sets.end());
    o.time = {spec.t0, spec.t1, 0.5};
    o.orbit_deg_per_s = spec.orbit;
    o.camera_path = spec.camera;
    o.warmup = 1;
    o.write_images = false;
    o.quiet = true;
    CullRun run;
    RenderResult r = render(rt(), spec.scene ? *spec.scene : layered_sheets(), o, [&](const Executor& e, size_t) {
        run.frames.push_back(read_resource(e.texture(resource)));
    });
    auto stat = [&](const std::string& name) {  // mean per measured frame
        for (const auto& p : r.profiler.passes())
            if (p.name == pass && p.stats.count(name)) return p.stats.at(name);
        return 0.0;
    };
    run.occluded = stat("chunks_occluded");
    run.phase1 = stat("chunks_phase1");
    run.phase2 = stat("chunks_phase2");
    run.frustum = stat("chunks_frustum_culled");
    run.segments = stat("segments");
    return run;
}
CullRun render_run(const std::string& graph, const std::string& pass, bool cull, const std::string& resource, double t0,
                   double t1, double orbit, double window = 2.0, int min_segments = 0) {
    return render_run(graph, pass, cull, resource, {.t0 = t0, .t1 = t1, .orbit = orbit, .window = window, .min_segments = min_segments});
}

// The small phantom: curved lines, whose level of detail keeps some points of every chunk and
// drops others, so a chunk's strip often ends in the next chunk.
const Scene& small_phantom() {
    static const Scene s = phantom::make_phantom(phantom::phantom_preset("small"));
    return s;
}

// Largest RMS (0..255) between the runs' frames. Runs of different frame counts or image sizes,
// or without frames, are a failure (and infinitely far apart), never "the same picture".
double worst_rms(const CullRun& a, const CullRun& b) {
    const double apart = std::numeric_limits<double>::infinity();
    if (a.frames.empty() || a.frames.size() != b.frames.size()) {
        ADD_FAILURE() << "runs of " << a.frames.size() << " and " << b.frames.size() << " frames: nothing to compare";
        return apart;
    }
    double worst = 0;
    for (size_t f = 0; f < a.frames.size(); ++f) {
        const Image &x = a.frames[f], &y = b.frames[f];
        if (x.width != y.width || x.height != y.height || x.channels != y.channels || x.pixels.empty() ||
            x.pixels.size() != y.pixels.size()) {
            ADD_FAILURE() << "frame " << f << ": " << x.width << "x" << x.height << "x" << x.channels << " against " << y.width
                          << "x" << y.height << "x" << y.channels;
            return apart;
        }
        double sq = 0;
        size_t n = 0;
        for (size_t i = 0; i < x.pixels.size(); ++i) {
            sq += double(x.pixels[i] - y.pixels[i]) * double(x.pixels[i] - y.pixels[i]);
            ++n;
        }
        worst = std::max(worst, 255.0 * std::sqrt(sq / double(std::max<size_t>(n, 1))));
    }
    return worst;
}

}  // namespace

TEST(Cull, HiddenChunksAreNotDrawnAndThePictureStaysTheSame) {
    // At rest, whole lines: the front sheet hides the seven behind it.
    const CullRun on = render_run("variant1_lineao.json", "gbuffer", true, "final", 4, 5, 0, 0.0);
    const CullRun off = render_run("variant1_lineao.json", "gbuffer", false, "final", 4, 5, 0, 0.0);
    ASSERT_EQ(on.frames.size(), 3u);
    EXPECT_GT(on.occluded, 100) << "the front sheet hides the chunks behind it";
    EXPECT_LT(on.segments, 0.5 * off.segments) << "culling draws fewer segments";
    EXPECT_EQ(worst_rms(on, off), 0.0) << "the same picture";
}

TEST(Cull, ASmallWindowSkipsTheOcclusionTest) {
    // Fewer data segments than cull_min_segments: frustum culling only (the depth read-back
    // would cost more than it saves), the same picture.
    const CullRun small = render_run("variant1_lineao.json", "gbuffer", true, "final", 4, 5, 0, 0.0, 1 << 30);
    const CullRun off = render_run("variant1_lineao.json", "gbuffer", false, "final", 4, 5, 0, 0.0);
    EXPECT_EQ(small.occluded, 0) << "no occlusion test below the threshold";
    EXPECT_EQ(small.segments, off.segments);
    EXPECT_EQ(worst_rms(small, off), 0.0);
}

TEST(Cull, WhileTheCameraOrbitsAndTheWindowMovesThePictureStaysTheSame) {
    // Five frames, the camera turning 20 degrees a second and the 2 s window moving.
    const CullRun on = render_run("variant1_lineao.json", "gbuffer", true, "final", 4, 6, 20);
    const CullRun off = render_run("variant1_lineao.json", "gbuffer", false, "final", 4, 6, 20);
    ASSERT_EQ(on.frames.size(), 5u);
    EXPECT_GT(on.phase2, 0) << "pathlets entering the window are drawn in phase 2";
    EXPECT_LE(worst_rms(on, off), 0.5) << "the picture is the same within 0.5/255 RMS";
}

TEST(Cull, IllustratedStreamlinesTooAndAJumpIsCaughtInPhaseTwo) {
    // An orbit of 200 degrees a second: 100 degrees between frames, a jump every frame.
    const CullRun on = render_run("isl.json", "isl", true, "final", 4, 6, 200, 0.0);
    const CullRun off = render_run("isl.json", "isl", false, "final", 4, 6, 200, 0.0);
    EXPECT_GT(on.occluded, 0);
    EXPECT_GT(on.phase2, 0) << "what the jump uncovers is drawn in phase 2";
    EXPECT_LE(worst_rms(on, off), 0.5);
}

TEST(Cull, TransparencyIsNotOcclusionCulled) {
    // fill_list keeps every fragment (depth ALWAYS; in variant2_oit, which binds its G-buffer, the
    // depth test after the shader and occlusion culling off): nothing may be hidden, the lists are the same.
    const CullRun on = render_run("variant2_oit.json", "fill_list", true, "final", 4, 6, 20);
    const CullRun off = render_run("variant2_oit.json", "fill_list", false, "final", 4, 6, 20);
    EXPECT_EQ(on.occluded, 0);
    EXPECT_EQ(worst_rms(on, off), 0.0);
    // At rest with whole lines, where the G-buffer pass hides over 100 chunks (the first test):
    // variant2_oit's G-buffer depth must not hide any of the lists' fragments either.
    const CullRun rest_on = render_run("variant2_oit.json", "fill_list", true, "final", 4, 5, 0, 0.0);
    const CullRun rest_off = render_run("variant2_oit.json", "fill_list", false, "final", 4, 5, 0, 0.0);
    EXPECT_EQ(rest_on.occluded, 0);
    EXPECT_EQ(worst_rms(rest_on, rest_off), 0.0);
}

TEST(Cull, TheChunksDrawTheUnculledSegmentsEachOnce) {
    // fill_list (OIT: frustum culling only, every fragment counts, the default framing shows
    // everything) on curved lines with the level of detail on: the chunks' strips, cut where
    // the window and the chunks cut a line, draw exactly the unculled draw's segments, each
    // once; with a width hook too (every 16th point kept). One time a run: the counts reported
    // are the warm-up frame's, the same picture.
    for (double window : {1.0, 0.0})
        for (const std::string hook : {"", "fade_width.geom"}) {
            const RunSpec spec{.scene = &small_phantom(), .t0 = 2.5, .t1 = 2.5, .window = window,
                               .sets = {"fill_list.width_hook=" + hook}};
            const CullRun on = render_run("variant2_oit.json", "fill_list", true, "final", spec);
            const CullRun off = render_run("variant2_oit.json", "fill_list", false, "final", spec);
            SCOPED_TRACE("window " + std::to_string(window) + ", width hook '" + hook + "'");
            EXPECT_GT(on.phase1, 0);
            EXPECT_GT(on.segments, 100);
            EXPECT_EQ(on.segments, off.segments) << "the same segments";
            EXPECT_EQ(worst_rms(on, off), 0.0) << "the same lists";
        }
}

TEST(Cull, WhatLiesOutsideTheViewIsNotDrawn) {
    // A close-up of the sheets' left part: the chunks to the right are outside the frustum.
    // (lod=0: at any level of detail a straight line is one segment, whose box is the line's.)
    const std::string camera = ::testing::TempDir() + "cull_close_up.json";
    {
        std::ofstream f(camera);
        f << R"({"keyframes": [{"time": 0, "eye": [2, 2, -6], "target": [2, 2, 0], "up": [0, 1, 0], "fov": 30}]})";
    }
    const RunSpec spec{.window = 0.0, .sets = {"gbuffer.lod=0"}, .camera = camera};
    const CullRun on = render_run("variant1_lineao.json", "gbuffer", true, "final", spec);
    const CullRun off = render_run("variant1_lineao.json", "gbuffer", false, "final", spec);
    EXPECT_GT(on.frustum, 100) << "the right part of every line is out of view";
    EXPECT_LT(on.segments, 0.5 * off.segments);
    EXPECT_EQ(worst_rms(on, off), 0.0);
}

TEST(Cull, ThePassKeepsItsOwnBindings) {
    // The kit_probe fixture colours its lines from its own storage buffer (binding point 0)
    // and texture (unit 0), which the culling's compute stages also use between the pass's
    // draws: every line pixel must still be (0.25, 0.5, 0), culled or not.
    auto run = [&](bool cull) {
        RenderOptions o;
        o.graph_path = std::string(PATHLET_SOURCE_DIR) + "/engine/lines/tests/graphs/kit_probe_depth.json";
        o.size = {192, 128};
        o.sets = {"probe.probe=bound", "probe.cull=" + std::string(cull ? "true" : "false"), "probe.cull_min_segments=0",
                  "window=0", "line_width=0.3"};
        o.time = {4, 5, 0.5};
        o.warmup = 0;
        o.write_images = false;
        o.quiet = true;
        CullRun run;
        RenderResult r = render(rt(), layered_sheets(), o,
                                [&](const Executor& e, size_t) { run.frames.push_back(read_resource(e.texture("color"))); });
        for (const auto& p : r.profiler.passes())
            if (p.name == "probe" && p.stats.count("chunks_occluded")) run.occluded = p.stats.at("chunks_occluded");
        return run;
    };
    const CullRun on = run(true), off = run(false);
    EXPECT_GT(on.occluded, 100) << "the culling ran, depth test and all";
    EXPECT_EQ(worst_rms(on, off), 0.0);
    size_t covered = 0, wrong = 0;
    for (const Image& img : on.frames)
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                if (img.at(x, y, 3) < 0.5f) continue;
                ++covered;
                wrong += std::fabs(img.at(x, y, 0) - 0.25f) > 0.01f || std::fabs(img.at(x, y, 1) - 0.5f) > 0.01f ||
                         img.at(x, y, 2) > 0.01f;
            }
    EXPECT_GT(covered, 1000u);
    EXPECT_EQ(wrong, 0u) << "pixels coloured from another buffer or texture";
}
