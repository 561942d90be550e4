// Waits for the GPU in the frame loop, counted per pass (engine/core/gpu_waits): every kind of
// wait a pass plugin can make is counted, its asynchronous twin is not, the engine's own waits
// and a pass's first frame are not faults, and no shipped graph waits except the exact
// references that declare it (PassTypeBuilder::waits_for_gpu), which do.
#include "error_text.hpp"
#include "executor.hpp"
#include "frame_capture.hpp"
#include "gpu_waits/gpu_waits.hpp"
#include "pass_registry.hpp"
#include "shipped_graphs.hpp"

#include <pathlet/gpu_fence.hpp>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace pathlet {
namespace {

const std::string kProbeGraph = std::string(PATHLET_TEST_SOURCE_DIR) + "/graphs/gpu_wait_probe.json";
constexpr int kWarmup = 1, kTimed = 3;  // four frames: the first, then three that must not wait

Runtime& rt() { return test_runtime({PATHLET_TEST_PLUGIN_DIR}); }

// Counting on (or off) and no simulated latency, for one test.
struct Counting {
    explicit Counting(bool on) {
        set_gpu_wait_counting(on ? 1 : 0);
        set_simulated_gpu_latency(0);
    }
    ~Counting() {
        set_gpu_wait_counting(-1);
        set_simulated_gpu_latency(-1);
    }
};

struct Counted {
    CompiledGraph graph;  // the compiled passes, by index as the counts
    std::vector<GpuWaitCount> counts;
};

Counted run(const Scene& scene, const std::string& graph, std::vector<std::string> sets,
            TimingBackend timing = TimingBackend::Auto) {
    RenderOptions opt;
    opt.graph_path = graph;
    opt.sets = std::move(sets);
    opt.size = {160, 90};
    opt.time.start = 2.0;  // the middle of the small phantom's 0..4 s
    opt.warmup = kWarmup;
    opt.repeat = kTimed;
    opt.write_images = false;
    opt.quiet = true;
    opt.timing = timing;
    Counted c;
    RenderResult r = render(rt(), scene, opt, [&](const Executor& ex, size_t) { c.counts = ex.gpu_waits(); });
    c.graph = r.compiled;
    return c;
}

Counted probe(const std::string& call, TimingBackend timing = TimingBackend::Auto) {
    return run(small_phantom_scene(), kProbeGraph, {"probe.call=" + call}, timing);
}

std::string line_of(const Counted& c, size_t i) {
    const CompiledPass& p = c.graph.passes.at(i);
    return gpu_wait_line(p.name, *p.type, Params(p.name, p.params, p.type), c.counts.at(i));
}

// What each `call` of the fixture is: the entry point counted, or "" for a call that does not wait.
struct Kind {
    std::string call, counted_as;
};
const std::vector<Kind> kKinds{
    {"finish", "glFinish"},
    {"get_buffer_sub_data", "glGetBufferSubData"},
    {"get_named_buffer_sub_data", "glGetNamedBufferSubData"},
    {"read_pixels", "glReadPixels"},
    {"read_pixels_into_pack_buffer", ""},
    {"get_texture_image", "glGetTextureImage"},
    {"get_texture_image_into_pack_buffer", ""},
    {"client_wait", "glClientWaitSync"},
    {"client_wait_poll", ""},
    {"server_wait", ""},
    {"sdk_fence_wait", "glClientWaitSync"},  // GpuFence::wait, libpathlet's own call
    {"query_result", "glGetQueryObjectuiv"},
    {"query_result_after_available", ""},
    {"map_read", "glMapNamedBufferRange"},
    {"map_read_persistent", ""},
    {"map_write", ""},
    {"none", ""},
};

TEST(GpuWaits, EveryKindOfWaitInAPassIsCountedAndItsAsynchronousTwinIsNot) {
    Counting on(true);
    for (const Kind& k : kKinds) {
        SCOPED_TRACE(k.call);
        const Counted c = probe(k.call);
        ASSERT_EQ(c.counts.size(), 1u);
        const GpuWaitCount& n = c.counts[0];
        if (k.counted_as.empty()) {
            EXPECT_EQ(n.first_frame + n.later, 0u) << line_of(c, 0);
            continue;
        }
        EXPECT_EQ(n.first_frame, 1u);  // the first frame's call, apart
        EXPECT_EQ(n.later, uint64_t(kTimed));
        EXPECT_EQ(n.frames, uint64_t(kTimed));
        EXPECT_EQ(n.first_waiting_frame, 1u);
        EXPECT_EQ(n.calls, (std::map<std::string, uint64_t>{{k.counted_as, uint64_t(kTimed)}}));
        const std::string line = line_of(c, 0);
        EXPECT_NE(line.find("GPU WAIT: pass 'probe' (gpu_wait_probe) waited for the GPU 3 times in 3 frames"),
                  std::string::npos)
            << line;
        EXPECT_NE(line.find(k.counted_as + " 3"), std::string::npos) << line;
    }
}

TEST(GpuWaits, NothingIsCountedWithoutTheMode) {
    Counting off(false);
    const Counted c = probe("finish");
    ASSERT_EQ(c.counts.size(), 1u);
    EXPECT_EQ(c.counts[0].first_frame + c.counts[0].later, 0u);
}

TEST(GpuWaits, TheModeIsOnUnderTheLatencySimulation) {
    set_gpu_wait_counting(-1);
    set_simulated_gpu_latency(2);
    const bool under_latency = gpu_wait_counting();
    set_simulated_gpu_latency(-1);
    EXPECT_TRUE(under_latency);
}

// The profiler's llvmpipe backend brackets every pass with glFinish, the executor waits for frames
// in flight: the engine's, around the pass, not in it.
TEST(GpuWaits, TheEnginesOwnWaitsAroundAPassDoNotCount) {
    Counting on(true);
    const Counted c = probe("none", TimingBackend::CpuFinish);
    ASSERT_EQ(c.counts.size(), 1u);
    EXPECT_EQ(c.counts[0].first_frame + c.counts[0].later, 0u) << line_of(c, 0);
}

TEST(GpuWaits, ADeclaredWaitIsAllowedOnlyWhenItsParameterSaysSo) {
    Counting on(true);
    const Counted c = run(small_phantom_scene(), kProbeGraph, {"probe.call=finish", "probe.allowed=true"});
    ASSERT_EQ(c.counts.size(), 1u);
    EXPECT_EQ(c.counts[0].later, uint64_t(kTimed));
    const std::string line = line_of(c, 0);
    EXPECT_EQ(line.find("GPU WAIT"), std::string::npos) << line;
    EXPECT_NE(line.find("as its type declares: a test fixture that waits when told to"), std::string::npos) << line;
}

struct Idle : Pass {
    void execute(PassContext&) override {}
};

TEST(GpuWaits, AWaitDeclaredWithAParameterThatIsNoBoolIsRefused) {
    for (const std::string when : {"n", "missing"}) {
        PassTypeInfo t = PassTypeBuilder("waiter", "test").param_int("n", 1, 0, 2, "n").waits_for_gpu("why", when).make<Idle>();
        t.plugin_file = "libwaiter.so";
        PassRegistry reg;
        EXPECT_EQ(test::error_text<std::runtime_error>([&] { reg.add(t); }),
                  "libwaiter.so: pass type 'waiter' declares that it waits for the GPU with '" + when +
                      "', which is not one of its bool parameters");
    }
    PassRegistry reg;
    EXPECT_NO_THROW(reg.add(PassTypeBuilder("waiter", "test").param_bool("b", false, "b").waits_for_gpu("why", "b").make<Idle>()));
}

TEST(GpuWaits, PassesDescribeSaysWhichPassTypesWaitAndWhy) {
    const PassRegistry& reg = rt().registry;
    for (const char* type : {"depth_peel", "resolve_exact", "fill_list"}) {
        ASSERT_NE(reg.find(type), nullptr) << type;
        const std::string d = reg.find(type)->describe();
        EXPECT_NE(d.find("waits for the GPU in the frame loop"), std::string::npos) << d;
        EXPECT_NE(d.find(reg.find(type)->gpu_wait_reason), std::string::npos) << d;
    }
    EXPECT_NE(reg.find("fill_list")->describe().find("frame loop (with never_drop): never_drop"), std::string::npos);
    EXPECT_EQ(reg.find("lineao")->describe().find("waits for the GPU"), std::string::npos);
}

// Every shipped graph, four frames: a pass that waits after its first frame fails, unless its type
// declares the wait (then it must still wait: the declaration is no stale excuse).
TEST(GpuWaits, NoShippedGraphWaitsInTheFrameLoopButTheReferencesThatDeclareIt) {
    Counting on(true);
    size_t allowed = 0;
    for (const ShippedGraph& g : shipped_graphs()) {
        SCOPED_TRACE(g.name);
        test_runtime();
        if (const std::string why = g.unsupported_here(); !why.empty()) {
            std::printf("skipped: %s\n", why.c_str());
            continue;
        }
        const Counted c = run(small_phantom_scene(), g.path, {});
        ASSERT_EQ(c.counts.size(), c.graph.passes.size());
        for (size_t i = 0; i < c.counts.size(); ++i) {
            const CompiledPass& p = c.graph.passes[i];
            if (gpu_wait_allowed(*p.type, Params(p.name, p.params, p.type))) {
                ++allowed;
                EXPECT_GT(c.counts[i].later, 0u) << g.name << ": pass '" << p.name << "' (" << p.type->type
                                                 << ") declares that it waits for the GPU, but it did not";
            } else {
                EXPECT_EQ(c.counts[i].later, 0u) << g.name << ": " << line_of(c, i);
            }
        }
    }
    EXPECT_GE(allowed, 3u) << "variant2_exact (fill_list with never_drop, resolve_exact) and variant2_depth_peel";
}

}  // namespace
}  // namespace pathlet
