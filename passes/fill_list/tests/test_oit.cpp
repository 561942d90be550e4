// Variant 2 (OIT through per-pixel linked lists) on real GL (llvmpipe): the resolve against a
// CPU blend of the very fragments in the lists, the opacity ramp, determinism, overflow
// detection and recovery, goldens, and the artefact of the faithful graph against the better one.
#include "oit_metric.hpp"

#include "executor.hpp"
#include "golden.hpp"
#include "oit_lists.hpp"

#include <map>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include <unistd.h>

namespace fs = std::filesystem;
using namespace pathlet;

namespace {

const std::string kSrc = PATHLET_SOURCE_DIR;
const std::string kHere = PATHLET_TEST_SOURCE_DIR;
const glm::ivec2 kSmall{160, 120};

const std::string& scratch() { return test_scratch_dir("pathlet_oit"); }

Frame render(const std::string& graph, std::vector<std::string> sets, const std::vector<std::string>& names,
             double t = 6.0, const Scene& scene = helix_bundle_scene(), glm::ivec2 size = kSmall) {
    RenderOptions opt;
    opt.graph_path = graph.find('/') == std::string::npos ? kHere + "/graphs/" + graph : graph;
    opt.sets = std::move(sets);
    opt.size = size;
    opt.time.start = t;
    return render_frame(test_runtime(), scene, opt, names);
}

// The lists as the GPU left them: heads and nodes, read in the frame callback.
struct Lists : OitLists {
    Image color;                           // resolve_list's output (top-down)
};

Lists render_lists(std::vector<std::string> sets) {
    RenderOptions opt;
    opt.graph_path = kHere + "/graphs/oit_only.json";
    opt.sets = std::move(sets);
    opt.size = kSmall;
    opt.time.start = opt.time.end = 6.0;
    opt.warmup = 0;
    opt.write_images = false;
    opt.quiet = true;
    Lists l;
    render(test_runtime(), helix_bundle_scene(), opt, [&](const Executor& ex, size_t) {
        static_cast<OitLists&>(l) = read_oit_lists(ex);
        l.color = read_resource(ex.texture("color"));
    });
    return l;
}


}  // namespace

TEST(Oit, ResolveEqualsACpuBlendOfTheSameFragments) {
    Lists l = render_lists({});
    size_t pixels = 0, layered = 0;
    for (int y = 0; y < l.height; ++y)
        for (int x = 0; x < l.width; ++x) {
            std::vector<glm::uvec4> frags;
            for (GLuint i = l.heads[size_t(y) * size_t(l.width) + size_t(x)]; i != 0xFFFFFFFFu; i = l.nodes.at(i).z)
                frags.push_back(l.nodes.at(i));
            if (frags.empty()) continue;
            ++pixels;
            layered += frags.size() > 1;
            // Depth, then line id, then colour; the 32 nearest; front to back until alpha 0.99.
            std::sort(frags.begin(), frags.end(), [](const glm::uvec4& a, const glm::uvec4& b) {
                float da, db;
                std::memcpy(&da, &a.y, 4);
                std::memcpy(&db, &b.y, 4);
                return da != db ? da < db : (a.w != b.w ? a.w < b.w : a.x < b.x);
            });
            if (frags.size() > 32) frags.resize(32);
            glm::dvec3 c(0.0);
            double alpha = 0.0;
            for (const auto& f : frags) {
                if (alpha >= 0.99) break;
                glm::dvec4 rgba = node_color(f.x);
                double w = (1.0 - alpha) * rgba.a;
                c += w * glm::dvec3(rgba);
                alpha += w;
            }
            c += (1.0 - alpha) * glm::dvec3(1.0);  // white background
            const int row = l.height - 1 - y;      // Image rows are top-down
            for (int k = 0; k < 3; ++k)
                ASSERT_NEAR(l.color.at(x, row, k), c[k], 1.0 / 255 + 1e-6) << "pixel " << x << "," << row << " channel " << k;
            ASSERT_EQ(l.color.at(x, row, 3), 1.0f);
        }
    EXPECT_GT(pixels, 500u);
    EXPECT_GT(layered, 100u) << "the scene must have overlapping fragments to test the blend";
}

TEST(Oit, OpacityRampsFromZeroAtTheTailToFullAndBackAtTheHead) {
    static const std::string camera = write_square_on_camera(scratch() + "/camera.json");
    RenderOptions opt;
    opt.graph_path = kHere + "/graphs/oit_only.json";
    opt.sets = {"window=4", "line_width=1.5", "fill_list.tail_fade=0.5", "fill_list.head_fade=0.25", "fill_list.halo=0"};
    opt.size = {400, 100};
    opt.camera_path = camera;
    opt.time.start = 8.0;  // the fast pathlet spans x = 1..17 (times 4..8)
    Frame f = render_frame(test_runtime(), two_speed_lines_scene(), opt, {"front_alpha"});
    const Image& a = f["front_alpha"];
    const float ppu = square_on_pixels_per_unit(100);
    auto col_of = [&](float x) { return int((x - 5.0f) * ppu + 200.0f); };
    auto alpha_at = [&](float x) {  // the largest alpha in the column (the line's centre rows)
        float m = 0;
        for (int y = 50; y < 100; ++y) m = std::max(m, a.at(col_of(x), y, 0));
        return m;
    };
    // Age runs from 0 at x = 17 (head) to 1 at x = 1 (tail): the tail ramp covers ages 0.5..1
    // (x 1..9), the head ramp ages 0..0.25 (x 13..17).
    EXPECT_LT(alpha_at(1.15f), 0.06f) << "alpha 0 at the tail";
    EXPECT_NEAR(alpha_at(3.0f), 0.25f, 0.05f);
    EXPECT_NEAR(alpha_at(5.0f), 0.5f, 0.05f);
    EXPECT_NEAR(alpha_at(11.0f), 1.0f, 0.01f) << "full in the body";
    EXPECT_NEAR(alpha_at(15.0f), 0.5f, 0.06f);
    EXPECT_LT(alpha_at(16.85f), 0.08f) << "back to 0 at the head";
    EXPECT_FALSE(has_nan(a));
}

TEST(Oit, OutputIsDeterministicAndFinite) {
    for (const char* g : {"variant2_oit", "variant2_oit_ao"}) {
        Frame a = render(kSrc + "/graphs/" + g + ".json", {"line_width=1.2", "window=3"}, {"final"});
        Frame b = render(kSrc + "/graphs/" + g + ".json", {"line_width=1.2", "window=3"}, {"final"});
        EXPECT_EQ(a["final"].pixels, b["final"].pixels) << g << ": two runs differ";
        EXPECT_FALSE(has_nan(a["final"])) << g;
    }
}

TEST(Oit, GBufferInTheListRasterEqualsTheGBufferPass) {
    // The same lines into a G-buffer twice: by fill_list beside its lists, and by the gbuffer
    // pass alone. Bit for bit the same, also when an overflow makes fill_list draw the frame again.
    for (const char* npp : {"4", "0.01"}) {
        Frame f = render("oit_gbuffer.json", {std::string("fill_list.nodes_per_pixel=") + npp},
                         {"color", "f_color", "f_normal_depth", "f_zoom", "f_depth", "f_line_id", "g_color",
                          "g_normal_depth", "g_zoom", "g_depth", "g_line_id"});
        for (const char* t : {"color", "normal_depth", "zoom", "depth", "line_id"})
            EXPECT_EQ(f[std::string("f_") + t].pixels, f[std::string("g_") + t].pixels) << t << ", nodes_per_pixel " << npp;
        size_t lines = 0;
        for (size_t i = 0; i < f["g_depth"].pixels.size(); ++i) lines += f["g_depth"].pixels[i] < 1.0f;
        EXPECT_GT(lines, 300u) << "the frame must show lines";
        // ... and the lists are those fill_list fills without a G-buffer.
        Frame plain = render("oit_only.json", {}, {"color"});
        EXPECT_EQ(f["color"].pixels, plain["color"].pixels) << "nodes_per_pixel " << npp;
    }
}

TEST(Oit, GBufferOutputsNeedTheDepthAndExcludeCoverage) {
    const std::string base = kHere + "/graphs/oit_gbuffer.json";
    auto error_of = [&](const std::string& from, const std::string& to, const std::string& from2 = "",
                        const std::string& to2 = "") {
        std::string text;
        {
            std::ifstream in(base);
            text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        }
        const size_t at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        text.replace(at, from.size(), to);
        if (!from2.empty()) text.replace(text.find(from2), from2.size(), to2);
        const std::string path = scratch() + "/oit_gbuffer_bad.json";
        std::ofstream(path) << text;
        try {
            render(path, {}, {"color"});
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    // Without `depth`, the G-buffer targets have no depth test to keep the nearest fragment.
    std::string e = error_of("\"depth\": \"f_depth\",", "", "\"coverage\": \"f_depth\"", "\"coverage\": \"g_depth\"");
    EXPECT_NE(e.find("need 'depth'"), std::string::npos) << e;
    EXPECT_NE(e.find("fill_list"), std::string::npos) << "the error names the pass: " << e;
    EXPECT_NE(e.find("oit_gbuffer_bad.json:/passes/1: "), std::string::npos) << "... its file and place: " << e;
    // coverage and the G-buffer's depth are one depth attachment.
    e = error_of("\"depth\": \"f_depth\",", "\"depth\": \"f_depth\", \"coverage\": \"f_coverage\",",
                 "\"f_depth\": { \"format\": \"depth24\" },",
                 "\"f_depth\": { \"format\": \"depth24\" }, \"f_coverage\": { \"format\": \"depth24\" },");
    EXPECT_NE(e.find("not both"), std::string::npos) << e;
}

TEST(Oit, ResolveRefusesPinsThatDoNotGoTogether) {
    // variant2_oit_ao (the core's AO) edited into wrong wirings of resolve_list's AO sources.
    std::string base;
    {
        std::ifstream in(kSrc + "/graphs/variant2_oit_ao.json");
        base.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    auto edit = [](std::string text, const std::vector<std::pair<std::string, std::string>>& swaps) {
        for (const auto& [from, to] : swaps) {
            const size_t at = text.find(from);
            EXPECT_NE(at, std::string::npos) << from;
            if (at != std::string::npos) text.replace(at, from.size(), to);
        }
        return text;
    };
    auto error_of = [&](const std::string& text) {
        const std::string path = scratch() + "/resolve_bad.json";
        std::ofstream(path) << text;
        try {
            // resolve_list's line width as fill_list's, which the records it reads need (the compiler
            // checks that first): what is refused here is the pins.
            render(path, {"line_width=1.2", "window=3", "resolve_list.line_width=1.2"}, {"final"});
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::pair<std::string, std::string> records_out{"\"outputs\": { \"nodes\": \"nodes\",",
                                                          "\"outputs\": { \"nodes\": \"nodes\", \"records\": \"records\","};
    const std::pair<std::string, std::string> records_res{"\"resources\": {",
                                                          "\"resources\": { \"records\": { \"kind\": \"buffer\" }, "
                                                          "\"density\": { \"kind\": \"buffer\", \"persistent\": true },"};
    const std::pair<std::string, std::string> density_pass{
        "\"passes\": [", "\"passes\": [ { \"name\": \"line_density\", \"type\": \"line_density\", "
                         "\"outputs\": { \"density\": \"density\" } },"};
    const std::string resolve_in = "\"inputs\": { \"heads\": \"heads\", \"nodes\": \"nodes\",";
    // records without density
    std::string e = error_of(edit(base, {records_res, records_out, {resolve_in, resolve_in + " \"records\": \"records\","}}));
    EXPECT_NE(e.find("connect both 'records'"), std::string::npos) << e;
    EXPECT_NE(e.find("resolve_bad.json:/passes/"), std::string::npos) << "names the file and the pass: " << e;
    // both sources of AO at once
    e = error_of(edit(base, {records_res, density_pass, records_out,
                             {resolve_in, resolve_in + " \"records\": \"records\", \"density\": \"density\","}}));
    EXPECT_NE(e.find("not both"), std::string::npos) << e;
    EXPECT_NE(e.find("resolve_list"), std::string::npos) << e;
    // the front outputs without records
    e = error_of(edit(base, {{"\"outputs\": { \"color\": \"lit\" } },",
                              "\"outputs\": { \"color\": \"lit\", \"front_normal_depth\": \"fnd\", \"front_line_id\": "
                              "\"fli\", \"front_ao\": \"fao\" } },"},
                             {"\"resources\": {", "\"resources\": { \"fnd\": { \"format\": \"rgba16f\" }, \"fli\": { "
                                                  "\"format\": \"r32i\" }, \"fao\": { \"format\": \"r16f\" },"},
                             {"\"outputs\": [ { \"resource\": \"final\"",
                              "\"outputs\": [ { \"resource\": \"fnd\" }, { \"resource\": \"final\""}}));
    EXPECT_NE(e.find("the front outputs need 'records'"), std::string::npos) << e;
    // the unedited graph renders
    EXPECT_EQ(error_of(base), "no error");
}

TEST(Oit, OverflowIsDetectedReportedAndRecovered) {
    Frame ample = render("oit_only.json", {"fill_list.nodes_per_pixel=64"}, {"color"});
    Frame tiny = render("oit_only.json", {"fill_list.nodes_per_pixel=0.01"}, {"color"});
    EXPECT_EQ(ample.stats["overflow_events"], 0.0);
    EXPECT_EQ(tiny.stats["overflow_events"], 1.0) << "the overflow must be reported";
    EXPECT_EQ(tiny.stats["dropped_fragments"], 0.0);
    EXPECT_GT(tiny.stats["capacity_nodes"], tiny.stats["nodes"] - 1) << "grown to hold the frame";
    EXPECT_EQ(tiny["color"].pixels, ample["color"].pixels) << "the re-rendered frame equals one with room enough";
}

// After the first frame fill_list never waits for its counter: a frame that needs more nodes
// than the buffer holds is found a frame late (it lost fragments, which is counted), the buffer
// grows with headroom, and the frames after it are whole again.
TEST(Oit, ALaterOverflowIsFoundWithoutWaitingAndTheNextFramesAreWhole) {
    RenderOptions opt;
    opt.graph_path = kHere + "/graphs/oit_only.json";
    opt.sets = {"fill_list.nodes_per_pixel=0.01"};
    opt.size = kSmall;
    opt.time = parse_time_range("0.2:6.2:3");  // few pathlets at 0.2 s, many later
    opt.repeat = 3;
    opt.warmup = 0;
    opt.write_images = false;
    opt.quiet = true;
    opt.keep = {"color"};
    Image last;
    RenderResult res = render(test_runtime(), helix_bundle_scene(), opt,
                              [&](const Executor& ex, size_t) { last = read_resource(ex.texture("color")); });
    std::map<std::string, double> stats;
    for (const auto& p : res.profiler.passes())
        for (const auto& [k, v] : p.stats) stats[k] = v;
    // The stats are means over the frames: the running total passed 1, and the loss was counted.
    EXPECT_GT(stats["overflow_events_total"], 1.0) << "the first frame's overflow and at least one found later";
    EXPECT_GT(stats["dropped_fragments"], 0.0) << "a frame that lost fragments says so";
    ASSERT_FALSE(res.incomplete_frames.empty()) << "and the run lists it (incomplete frames: N of M)";
    EXPECT_EQ(res.incomplete_frames.front(), 3u) << "the first frame at 3.2 s is the first to outgrow the buffer";
    EXPECT_LT(res.incomplete_frames.back(), res.frames - 1) << "the last frame is whole";
    Frame ample = render("oit_only.json", {"fill_list.nodes_per_pixel=64"}, {"color"}, 6.2);
    EXPECT_EQ(last.pixels, ample["color"].pixels) << "the last frames have room again";
}

TEST(Oit, FragmentsBeyondTheMemoryCapAreCountedAsDropped) {
    Frame capped = render("oit_only.json", {"fill_list.nodes_per_pixel=0.01", "fill_list.max_memory_mb=0.01"}, {"color"});
    EXPECT_GT(capped.stats["dropped_fragments"], 0.0) << "a frame that loses fragments must say so";
    EXPECT_LE(capped.stats["capacity_nodes"], 0.01 * 1048576 / 16 + 1);
}

TEST(Oit, GoldensOfBothGraphs) {
    for (const char* g : {"variant2_oit", "variant2_oit_ao"}) {
        Frame f = render(kSrc + "/graphs/" + g + ".json", {"line_width=1.2", "window=3", "overlay=false"}, {"final"});
        EXPECT_TRUE(matches_golden(f["final"], kHere + "/goldens/" + g + ".png")) << g;
    }
}

TEST(Oit, BetterGraphDarkensFadedFragmentsFarLessThanTheFaithfulOne) {
    oit_test::Artefact res[2];
    int k = 0;
    for (const char* g : {"variant2_oit", "variant2_oit_ao"}) {
        oit_test::MetricGraph m = oit_test::metric_graph(kSrc + "/graphs/" + g + ".json", scratch());
        Frame f = render(m.path, {"line_width=1.2", "window=3", "strength=2"}, {m.final_name, m.unlit_name, m.front_alpha_name});
        res[k++] = oit_test::measure_artefact(f, m);
    }
    ASSERT_GT(res[0].pixels, 50u);
    EXPECT_GT(res[0].darkening, 0.02) << "the faithful graph shows the study's artefact";
    EXPECT_LT(res[1].darkening, 0.25 * res[0].darkening)
        << "faithful " << 255 * res[0].darkening << "/255, better " << 255 * res[1].darkening << "/255";
}
