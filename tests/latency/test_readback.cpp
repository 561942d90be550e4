// GpuReadback and ReadbackRing on their own, on real GL, with the GPU's latency simulated
// (pathlet/gpu_fence.hpp): copies made without polling stay in flight, nothing is handed out
// before its fence may have signalled, and then every copy is, in order, with its tag.
#include "frame_capture.hpp"
#include "renderer.hpp"
#include "frames/readback_ring.hpp"
#include "profiler/profiler.hpp"

#include <pathlet/gpu_fence.hpp>
#include <pathlet/gpu_readback.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlet {
namespace {

// Sets the simulated latency for one test and restores the environment's after it.
struct Latency {
    explicit Latency(int k) { set_simulated_gpu_latency(k); }
    ~Latency() { set_simulated_gpu_latency(-1); }
};

// A small buffer whose first word the test sets before each copy.
struct Source {
    GLuint id = 0;
    Source() {
        test_runtime();  // the GL context
        glCreateBuffers(1, &id);
        glNamedBufferStorage(id, 16, nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    ~Source() { glDeleteBuffers(1, &id); }
    void set(uint32_t v) const {
        const uint32_t words[4] = {v, ~v, v * 3u, 7u};
        glNamedBufferSubData(id, 0, sizeof words, words);
    }
};

struct Seen {
    uint32_t value = 0;
    uint64_t tag = 0, frame = 0;
};

// Frames until the clock is on a multiple of k (a fresh start for the burst rule).
void advance_to_multiple(int k) {
    while (gpu_frame() % uint64_t(k) != 0) advance_gpu_frame();
}

TEST(GpuReadback, EveryCopyReachesItsOwnerInOrderWithItsTagOnlyAfterTheLatencyAndInBursts) {
    const int k = 3;
    Latency latency(k);
    Source src;
    GpuReadback rb(16, 4);
    advance_to_multiple(k);
    const uint64_t first = gpu_frame();
    const int n = 10;  // more copies than the ring's first slots: it must grow, not drop
    for (int i = 0; i < n; ++i) {
        advance_gpu_frame();
        src.set(uint32_t(100 + i));
        rb.copy(src.id, 0, uint64_t(1000 + i), uint64_t(i));
    }
    glFinish();  // the GPU is done: only the simulated latency holds the results back
    EXPECT_EQ(rb.in_flight(), size_t(n)) << "copy() must not hand out (or drop) results nobody polled";
    EXPECT_GE(rb.slots(), size_t(n)) << "the ring grows while every slot is in flight";
    EXPECT_EQ(rb.waits(), 0u);

    std::vector<Seen> seen;
    auto take = [&](const GpuReadback::Result& r) {
        seen.push_back({*static_cast<const uint32_t*>(r.data), r.tag, r.frame});
    };
    // Poll every frame: results come only on multiples of k, and each no earlier than k frames
    // after its copy.
    for (int f = 0; f < 3 * k && seen.size() < size_t(n); ++f) {
        const size_t before = seen.size();
        const size_t got = rb.poll(take);
        EXPECT_EQ(got, seen.size() - before);
        if (got) { EXPECT_EQ(gpu_frame() % uint64_t(k), 0u) << "results arrive in bursts, on multiples of K"; }
        if (gpu_frame() % uint64_t(k) == 0) {  // a burst: every copy at least K frames old, no other
            size_t due = 0;
            for (int i = 0; i < n; ++i) due += first + 1 + uint64_t(i) + uint64_t(k) <= gpu_frame();
            EXPECT_EQ(seen.size(), due) << "at frame " << gpu_frame() - first;
        }
        advance_gpu_frame();
    }
    ASSERT_EQ(seen.size(), size_t(n)) << "every copy is handed out once the latency has passed";
    for (int i = 0; i < n; ++i) {
        EXPECT_EQ(seen[size_t(i)].value, uint32_t(100 + i)) << i;
        EXPECT_EQ(seen[size_t(i)].tag, uint64_t(1000 + i)) << i;
        EXPECT_EQ(seen[size_t(i)].frame, uint64_t(i)) << i;
    }
    EXPECT_EQ(rb.in_flight(), 0u);
}

TEST(GpuReadback, ACopyThatFindsEverySlotInFlightWaitsForTheOldestAndLosesNothing) {
    Latency latency(1000);  // no fence is seen as signalled while this runs
    Source src;
    GpuReadback rb(16, 2, 2);
    const int n = 5;
    for (int i = 0; i < n; ++i) {
        advance_gpu_frame();
        src.set(uint32_t(7 * i));
        rb.copy(src.id, 0, uint64_t(i), uint64_t(i));
    }
    EXPECT_EQ(rb.slots(), 2u);
    EXPECT_EQ(rb.waits(), size_t(n - 2)) << "each copy beyond the slots waited for the oldest (counted)";
    EXPECT_EQ(rb.in_flight(), size_t(n));
    std::vector<Seen> seen;
    auto take = [&](const GpuReadback::Result& r) {
        seen.push_back({*static_cast<const uint32_t*>(r.data), r.tag, r.frame});
    };
    // The copies waited for are handed out without waiting; the two in their slots are not yet.
    EXPECT_EQ(rb.poll(take), size_t(n - 2));
    EXPECT_EQ(rb.drain(take), 2u) << "drain() waits for the rest (a real wait, never simulated)";
    ASSERT_EQ(seen.size(), size_t(n));
    for (int i = 0; i < n; ++i) {
        EXPECT_EQ(seen[size_t(i)].value, uint32_t(7 * i)) << i;
        EXPECT_EQ(seen[size_t(i)].tag, uint64_t(i)) << i;
    }
}

TEST(GpuReadback, PollNewestIsForStatisticsAndSkipsOlderCopies) {
    Latency latency(0);
    Source src;
    GpuReadback rb(16);
    for (uint32_t v : {5u, 6u, 7u}) {
        src.set(v);
        rb.copy(src.id, 0, v);
    }
    glFinish();
    const void* p = rb.poll_newest();
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(*static_cast<const uint32_t*>(p), 7u);
    EXPECT_EQ(rb.latest_tag(), 7u);
    EXPECT_EQ(rb.poll_newest(), nullptr) << "nothing new";
}

// A 4x2 RGBA8 texture whose first texel holds `v`.
struct SmallTexture {
    GLuint id = 0;
    SmallTexture() {
        test_runtime();
        glCreateTextures(GL_TEXTURE_2D, 1, &id);
        glTextureStorage2D(id, 1, GL_RGBA8, 4, 2);
    }
    ~SmallTexture() { glDeleteTextures(1, &id); }
    void set(uint8_t v) const {
        std::vector<uint8_t> px(4 * 2 * 4, 0);
        px[0] = v;
        glTextureSubImage2D(id, 0, 0, 0, 4, 2, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    }
};

TEST(ReadbackRing, FramesStayInFlightUntilTheirFenceAndEndFrameWaitsOnlyWhenTheRingIsFull) {
    Latency latency(1000);  // no fence is seen as signalled: only end_frame's full ring may wait
    SmallTexture tex;
    const size_t depth = 3;
    ReadbackRing ring(depth);
    std::vector<int> done;  // the first byte of each copy handed over, in order
    auto copy = [&](int v) {
        tex.set(uint8_t(v));
        ring.copy(tex.id, 4, 2, GL_RGBA, GL_UNSIGNED_BYTE, 4,
                  [&](PackedPixels&& px) { done.push_back(px.size ? px.data[0] : -1); }, "test");
    };
    for (size_t f = 0; f < depth; ++f) {
        advance_gpu_frame();
        copy(int(10 + f));
        ring.end_frame();
        ring.poll();
        EXPECT_EQ(ring.in_flight(), f + 1) << "end_frame() with room left must not wait";
        EXPECT_TRUE(done.empty()) << "nothing is handed over before its fence";
    }
    EXPECT_EQ(ring.buffers(), depth);
    advance_gpu_frame();
    copy(13);
    ring.end_frame();  // depth + 1 frames: waits for the oldest only
    EXPECT_EQ(ring.in_flight(), depth);
    EXPECT_EQ(done, (std::vector<int>{10}));
    ring.drain();
    EXPECT_EQ(done, (std::vector<int>{10, 11, 12, 13})) << "every frame, in order";
    EXPECT_EQ(ring.in_flight(), 0u);
    EXPECT_LE(ring.buffers(), depth + 1) << "pack buffers are recycled, not made per frame";
}

TEST(ReadbackRing, PollTakesWhatIsReadyOnceTheLatencyHasPassed) {
    const int k = 2;
    Latency latency(k);
    SmallTexture tex;
    ReadbackRing ring(8);
    std::vector<int> done;
    advance_to_multiple(k);
    for (int f = 0; f < 6; ++f) {
        advance_gpu_frame();
        tex.set(uint8_t(f));
        ring.copy(tex.id, 4, 2, GL_RGBA, GL_UNSIGNED_BYTE, 4,
                  [&](PackedPixels&& px) { done.push_back(px.size ? px.data[0] : -1); }, "test");
        ring.end_frame();
        glFinish();
        const size_t before = done.size();
        ring.poll();
        if (done.size() > before) { EXPECT_EQ(gpu_frame() % uint64_t(k), 0u); }
        EXPECT_LE(done.size(), size_t(f + 1 >= k ? f + 1 - k + 1 : 0)) << "frame " << f << ": a result came early";
    }
    ring.drain();
    EXPECT_EQ(done, (std::vector<int>{0, 1, 2, 3, 4, 5}));
}


// The viewer's resizes: a copy size no longer used leaves no buffers behind. The window grows
// five times (a copy of each size for a few frames): the ring holds the last size's buffers
// alone, never a set per size ever copied (a smaller size's buffer fits no larger copy).
TEST(ReadbackRing, BuffersOfASizeNoLongerCopiedAreFreed) {
    Latency latency(0);
    test_runtime();
    const int widths[5] = {4, 8, 16, 32, 64};
    GLuint tex[5] = {0, 0, 0, 0, 0};
    glCreateTextures(GL_TEXTURE_2D, 5, tex);
    for (int i = 0; i < 5; ++i) glTextureStorage2D(tex[i], 1, GL_RGBA8, widths[i], 2);
    const size_t depth = 2;
    ReadbackRing ring(depth);
    size_t handed = 0, most = 0;
    for (int i = 0; i < 5; ++i)
        for (int f = 0; f < 4; ++f) {
            advance_gpu_frame();
            ring.copy(tex[i], widths[i], 2, GL_RGBA, GL_UNSIGNED_BYTE, 4, [&](PackedPixels&&) { ++handed; }, "test");
            ring.end_frame();
            ring.poll();
            most = std::max(most, ring.buffers());
        }
    ring.drain();
    EXPECT_EQ(handed, 20u) << "every copy handed over";
    EXPECT_LE(most, 2 * (depth + 1)) << "buffers held at any time";
    EXPECT_LE(ring.buffers(), depth + 1) << "only the size still copied keeps buffers";
    glDeleteTextures(5, tex);
}

// A GPU that never signals: a blocking wait gives up after the limit, naming the frame its fence
// was issued in; inside a pass the executor adds the pass's name.
TEST(GpuFence, AWaitOnAGpuThatNeverSignalsGivesUpNamingTheFrameAndThePass) {
    struct Hung {
        Hung() {
            set_gpu_wait_limit(0.3);
            set_simulated_gpu_hang(true);
        }
        ~Hung() {
            set_simulated_gpu_hang(false);
            set_gpu_wait_limit(0);
        }
    };
    test_runtime();
    {
        GpuFence f = GpuFence::insert();
        const uint64_t issued = f.frame();
        Hung hung;
        try {
            f.wait();
            ADD_FAILURE() << "a wait on a GPU that never signals returned";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("frame " + std::to_string(issued)), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("PATHLET_GPU_WAIT_LIMIT"), std::string::npos) << e.what();
        }
    }
    // fill_list reads its node count back without waiting after the first frame (which waits);
    // the end of the run waits for the second frame's. Two frames: the frames in flight never
    // wait before it.
    RenderOptions opt;
    opt.graph_path = std::string(PATHLET_SOURCE_DIR) + "/graphs/variant2_oit.json";
    opt.size = {64, 36};
    opt.time = {2.0, 2.04, 0.04};
    opt.warmup = 0;
    opt.write_images = false;
    opt.quiet = true;
    Hung hung;
    try {
        render(test_runtime(), small_phantom_scene(), opt);
        ADD_FAILURE() << "a render on a GPU that never signals finished";
    } catch (const std::exception& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("pass 'fill_list'"), std::string::npos) << m;
        EXPECT_NE(m.find("did not finish the work of frame"), std::string::npos) << m;
    }
}

// The viewer's timing: ready timer queries are collected without waiting, the rest carry over.
TEST(Profiler, CollectReadyNeverWaitsAndFramesInFlightCarryOver) {
    const int k = 3;
    Latency latency(k);
    Runtime& rt = test_runtime();
    Profiler p;
    p.set_warmup_frames(0);
    p.init(TimingBackend::GlTimestamp, rt.gl->renderer());
    ASSERT_EQ(p.backend(), TimingBackend::GlTimestamp) << p.backend_description();
    advance_to_multiple(k);
    for (int f = 0; f < 5; ++f) {  // frames issued at 1..5 after a multiple of k
        advance_gpu_frame();
        p.begin_frame(uint64_t(f));
        p.begin_pass("clear");
        glClear(GL_COLOR_BUFFER_BIT);
        p.end_pass();
        p.end_frame();
    }
    glFinish();
    advance_gpu_frame();  // a multiple of k: frames issued at least k frames before are due
    p.collect_ready();
    EXPECT_EQ(p.frames_timed(), 3u) << "the frames issued 1..3 after are due at 6, the two after them not yet";
    p.forget_timed();
    EXPECT_EQ(p.frames_recorded(), 2u) << "frames still in flight carry over";
    p.flush();  // waits for them (the end of a run)
    EXPECT_EQ(p.frames_timed(), 2u);
    EXPECT_EQ(p.gpu_frames_dropped(), 0u);
    p.release_gl();
}

}  // namespace
}  // namespace pathlet
