// The render loop under PATHLET_SIMULATE_GPU_LATENCY=K (the environment's K, 3 when unset; ctest
// runs this suite under K = 1, 3 and 6): counts that arrive late and in bursts lose nothing, every
// frame that lost fragments is listed, pictures do not change, and `pathlet render` ends with the
// incomplete-frames line.
#include "executor.hpp"
#include "frame_capture.hpp"

#include <pathlet/gpu_fence.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

namespace pathlet {
namespace {

namespace fs = std::filesystem;
const std::string kGraphs = std::string(PATHLET_SOURCE_DIR) + "/graphs/";
const glm::ivec2 kSize{160, 120};

// The latency of this run: the environment's, or 3 when it sets none.
int latency_k() {
    set_simulated_gpu_latency(-1);
    const int k = simulated_gpu_latency();
    return k > 0 ? k : 3;
}

struct Rendered {
    std::vector<Image> final;  // the first output of every frame
    std::vector<size_t> incomplete;
    size_t frames = 0;
};

// Renders `graph` over `time` on the small phantom with the latency `k` (0: off).
Rendered render_with(int k, const std::string& graph, const std::vector<std::string>& sets, const std::string& time,
                     bool read = false, glm::ivec2 size = kSize) {
    set_simulated_gpu_latency(k);
    RenderOptions opt;
    opt.graph_path = kGraphs + graph + ".json";
    opt.sets = sets;
    opt.size = size;
    opt.time = parse_time_range(time);
    opt.write_images = false;
    opt.quiet = true;
    Rendered run;
    std::string out;
    if (read) {  // the first output, kept out of the pool to be read after the frame
        GraphFile g = test_runtime().load_graph(opt.graph_path, opt.sets);
        out = g.outputs.front().resource;
        opt.keep.push_back(out);
    }
    RenderResult r = render(test_runtime(), small_phantom_scene(), opt, [&](const Executor& ex, size_t) {
        if (read) run.final.push_back(read_resource(ex.texture(out)));
    });
    set_simulated_gpu_latency(-1);
    run.incomplete = r.incomplete_frames;
    run.frames = r.frames;
    return run;
}

std::vector<size_t> all_frames(size_t n) {
    std::vector<size_t> v(n);
    for (size_t i = 0; i < n; ++i) v[i] = i;
    return v;
}

// 20 frames, more than 3K: counts arrive in bursts of several before the run ends (drain() takes
// the last ones), so a burst that handed out only its newest count would lose frames here.
TEST(Latency, CappedNodeMemoryListsEveryFrameAsIncompleteAsWithoutTheMode) {
    const int k = latency_k();
    const glm::ivec2 small{96, 72};
    for (const auto& [graph, cap] : {std::pair<std::string, std::string>{"variant2_oit", "fill_list.max_memory_mb=0.01"},
                                     {"variant4_opacity", "opacity_lists.max_memory_mb=0.01"}}) {
        const Rendered late = render_with(k, graph, {cap, "window=2"}, "2:3.9:0.1", false, small);
        const Rendered now = render_with(0, graph, {cap, "window=2"}, "2:3.9:0.1", false, small);
        ASSERT_EQ(late.frames, 20u) << graph;
        EXPECT_EQ(now.incomplete, all_frames(20)) << graph << ": every frame overflows its capped memory";
        EXPECT_EQ(late.incomplete, now.incomplete) << graph << " under K = " << k << ": a late count was lost";
    }
}

// Pulsatile flow with a short window: diastole draws few fragments, systole many. Starting with
// fill_list's smallest buffer, a systole frame overflows; its count arrives up to 2K - 1 frames
// later and the buffer grows. Every frame that differs from a render with room enough is listed,
// and no more than 2K frames are.
TEST(Latency, AJumpBetweenDiastoleAndSystoleListsEveryFrameThatDiffersAndAtMost2K) {
    const int k = latency_k();
    const std::string time = "0.8:3.95:0.45";  // 8 frames, alternating phases of the 1 s cycle
    const Rendered tight = render_with(k, "variant2_oit", {"window=0.15", "fill_list.nodes_per_pixel=0.01"}, time, true);
    const Rendered ample = render_with(0, "variant2_oit", {"window=0.15", "fill_list.nodes_per_pixel=64"}, time, true);
    ASSERT_EQ(tight.final.size(), 8u);
    ASSERT_EQ(ample.final.size(), 8u);
    EXPECT_TRUE(ample.incomplete.empty());
    ASSERT_FALSE(tight.incomplete.empty()) << "no frame overflowed: the test says nothing";
    EXPECT_LE(tight.incomplete.size(), size_t(2 * k));
    const std::set<size_t> listed(tight.incomplete.begin(), tight.incomplete.end());
    size_t differ = 0;
    for (size_t i = 0; i < 8; ++i)
        if (tight.final[i].pixels != ample.final[i].pixels) {
            ++differ;
            EXPECT_TRUE(listed.count(i)) << "frame " << i << " lost fragments and was not listed (K = " << k << ")";
        }
    EXPECT_GT(differ, 0u) << "an overflow that changed no pixel: the test says nothing";
}

TEST(Latency, ShippedVariantsRenderTheSamePixelsWithAndWithoutTheMode) {
    const int k = latency_k();
    for (const std::string graph : {"variant1_lineao", "variant2_oit", "variant3_geomfade", "variant4_opacity", "isl"}) {
        const Rendered late = render_with(k, graph, {}, "1:1.6:0.2", true);
        const Rendered now = render_with(0, graph, {}, "1:1.6:0.2", true);
        ASSERT_EQ(late.final.size(), 4u) << graph;
        ASSERT_EQ(now.final.size(), 4u) << graph;
        for (size_t i = 0; i < 4; ++i)
            EXPECT_TRUE(late.final[i].pixels == now.final[i].pixels) << graph << " frame " << i << " under K = " << k;
        EXPECT_EQ(late.incomplete, now.incomplete) << graph;
    }
}

// ---- the command ------------------------------------------------------------------------------

struct Command {
    int status = -1;
    std::vector<std::string> err;  // stderr lines
};

Command run_cli(const std::string& args, const fs::path& dir, const std::string& env = "") {
    const fs::path err = dir / "stderr.txt";
    const std::string cmd = (env.empty() ? "" : "env '" + env + "' ") + "'" + std::string(PATHLET_CLI) + "' " + args +
                            " > /dev/null 2> '" + err.string() + "'";
    Command c;
    const int s = std::system(cmd.c_str());
    c.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
    std::ifstream in(err);
    for (std::string line; std::getline(in, line);) c.err.push_back(line);
    return c;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
}

const fs::path& phantom_file() {
    static const fs::path f = [] {
        const fs::path dir = test_scratch_dir("pathlet_latency");
        const fs::path p = fs::path(dir) / "small.pathlet";
        const Command c = run_cli("phantom --preset small -o '" + p.string() + "'", dir);
        if (c.status != 0) throw std::runtime_error("pathlet phantom failed: " + joined(c.err));
        return p;
    }();
    return f;
}

size_t pngs(const fs::path& dir) {
    size_t n = 0;
    if (fs::exists(dir))
        for (const auto& e : fs::recursive_directory_iterator(dir)) n += e.path().extension() == ".png";
    return n;
}

TEST(Latency, RenderEndsWithOneIncompleteFramesLineNamedAsTheFilesAndExitsZero) {
    const fs::path dir = fs::path(test_scratch_dir("pathlet_latency")) / "cli";
    fs::create_directories(dir);
    const std::string base = "render variant2_oit --data '" + phantom_file().string() +
                             "' --size 160x120 --time 1:1.7:0.1 --quiet --set fill_list.max_memory_mb=0.02 ";
    // Every frame capped: all eight, written anyway.
    Command all = run_cli(base + "--out '" + (dir / "all").string() + "'", dir);
    ASSERT_EQ(all.status, 0) << joined(all.err);
    ASSERT_FALSE(all.err.empty());
    EXPECT_EQ(all.err.back(), "incomplete frames: 8 of 8 (0, 1, 2, 3, 4, 5, 6, 7)") << joined(all.err);
    EXPECT_EQ(std::count_if(all.err.begin(), all.err.end(),
                            [](const std::string& l) { return l.rfind("incomplete frames:", 0) == 0; }),
              1) << "exactly one such line";
    EXPECT_EQ(pngs(dir / "all"), 8u);
    // A shard's frames keep the sequence's numbers, as its files do.
    Command shard = run_cli(base + "--shard 1/2 --out '" + (dir / "shard").string() + "'", dir);
    ASSERT_EQ(shard.status, 0) << joined(shard.err);
    EXPECT_EQ(shard.err.back(), "incomplete frames: 4 of 4 (1, 3, 5, 7)") << joined(shard.err);
    EXPECT_TRUE(fs::exists(dir / "shard" / "variant2_oit" / "00003.png"));
    // Room enough: no such line.
    Command whole = run_cli("render variant2_oit --data '" + phantom_file().string() +
                                "' --size 160x120 --time 1:1.3:0.1 --quiet --no-images",
                            dir);
    ASSERT_EQ(whole.status, 0) << joined(whole.err);
    for (const auto& l : whole.err) EXPECT_EQ(l.find("incomplete frames"), std::string::npos) << l;
}

TEST(Latency, ABadLatencyOrFramesInFlightIsAUsageErrorNamingTheVariable) {
    const fs::path dir = fs::path(test_scratch_dir("pathlet_latency")) / "bad_env";
    fs::create_directories(dir);
    const std::string render = "render isl --data '" + phantom_file().string() + "' --size 96x72 --time 1 --quiet --out '" +
                               (dir / "out").string() + "'";
    for (const auto& [var, value] : {std::pair<std::string, std::string>{"PATHLET_SIMULATE_GPU_LATENCY", "-2"},
                                     {"PATHLET_SIMULATE_GPU_LATENCY", "3x"},
                                     {"PATHLET_FRAMES_IN_FLIGHT", "0"},
                                     {"PATHLET_FRAMES_IN_FLIGHT", "many"}}) {
        const Command c = run_cli(render, dir, var + "=" + value);
        EXPECT_EQ(c.status, 2) << var << "=" << value << "\n" << joined(c.err);
        ASSERT_FALSE(c.err.empty());
        EXPECT_NE(c.err.back().find(var + "='" + value + "'"), std::string::npos) << c.err.back();
        EXPECT_FALSE(fs::exists(dir / "out")) << "nothing written";
    }
}

}  // namespace
}  // namespace pathlet
