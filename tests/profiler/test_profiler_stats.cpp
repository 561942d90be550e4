// compute_stats and the recording rules (warm-up exclusion, per-frame pass totals), driven
// by a fake clock so every number is known.
#include "fake_profile.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <thread>

namespace pathlet {
namespace {

TEST(ComputeStats, InterpolatesPercentilesLinearly) {
    Profiler::Stats s = compute_stats({4, 1, 3, 2});  // unsorted on purpose
    EXPECT_EQ(s.n, 4u);
    EXPECT_DOUBLE_EQ(s.min, 1);
    EXPECT_DOUBLE_EQ(s.max, 4);
    EXPECT_DOUBLE_EQ(s.mean, 2.5);
    EXPECT_DOUBLE_EQ(s.median, 2.5);        // halfway between 2 and 3
    EXPECT_NEAR(s.p5, 1.15, 1e-12);          // pos 0.15 between 1 and 2
    EXPECT_NEAR(s.p95, 3.85, 1e-12);         // pos 2.85 between 3 and 4
}

TEST(ComputeStats, OddCountMedianIsMiddleSample) {
    Profiler::Stats s = compute_stats({10, 30, 20, 50, 40});
    EXPECT_DOUBLE_EQ(s.median, 30);
    EXPECT_NEAR(s.p5, 12, 1e-12);  // pos 0.2 -> 10 + 0.2 * 10
    EXPECT_NEAR(s.p95, 48, 1e-12); // pos 3.8 -> 40 + 0.8 * 10
}

TEST(ComputeStats, SingleAndEmpty) {
    Profiler::Stats one = compute_stats({7});
    EXPECT_EQ(one.n, 1u);
    EXPECT_DOUBLE_EQ(one.median, 7);
    EXPECT_DOUBLE_EQ(one.p5, 7);
    EXPECT_DOUBLE_EQ(one.p95, 7);
    Profiler::Stats none = compute_stats({});
    EXPECT_EQ(none.n, 0u);
    EXPECT_DOUBLE_EQ(none.median, 0);
}

TEST(TimingBackend, ParsesTheFourWords) {
    EXPECT_EQ(parse_timing_backend("auto"), TimingBackend::Auto);
    EXPECT_EQ(parse_timing_backend("gpu"), TimingBackend::GlTimestamp);
    EXPECT_EQ(parse_timing_backend("finish"), TimingBackend::CpuFinish);
    EXPECT_EQ(parse_timing_backend("cpu"), TimingBackend::CpuTime);
    EXPECT_STREQ(to_string(TimingBackend::CpuTime), "cpu");
    try {
        parse_timing_backend("fast");
        FAIL() << "no exception";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("fast"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("finish"), std::string::npos);
    }
}

TEST(TimingBackend, AutoPicksFinishForSoftwareRenderers) {
    Profiler p;
    p.init(TimingBackend::Auto, "llvmpipe (LLVM 15.0.6, 256 bits)");
    EXPECT_EQ(p.backend(), TimingBackend::CpuFinish);
    EXPECT_NE(p.backend_description().find("llvmpipe"), std::string::npos);
    EXPECT_NE(p.backend_description().find("glFinish"), std::string::npos);
    EXPECT_TRUE(is_software_renderer("SwiftShader Device (Subzero)"));
    EXPECT_TRUE(is_software_renderer("softpipe"));
    EXPECT_FALSE(is_software_renderer("NVIDIA H100 PCIe/PCIe/SSE2"));
}

TEST(TimingBackend, GpuWithoutTimestampsFallsBackAndSaysSo) {
    // No context is current in this test: GL_QUERY_COUNTER_BITS reads as 0.
    Profiler p;
    p.init(TimingBackend::Auto, "NVIDIA H100 PCIe/PCIe/SSE2");
    EXPECT_EQ(p.backend(), TimingBackend::CpuFinish);
    EXPECT_NE(p.backend_description().find("unavailable"), std::string::npos);
}

// A pass that sleeps 120 ms and one that works: the process CPU time bills the work and not the
// sleep (a busy machine's waiting), the glFinish-bracketed clock both; the recording time stays
// the wall clock under either.
TEST(TimingBackend, CpuTimeCountsWorkNotWaiting) {
    auto run = [](TimingBackend b) {
        Profiler p;
        p.set_warmup_frames(0);
        p.init(b, "llvmpipe");
        p.begin_frame(0);
        p.begin_pass("sleep");
        std::this_thread::sleep_for(std::chrono::milliseconds(120));
        p.end_pass();
        p.begin_pass("work");
        volatile double x = 0;
        for (int i = 0; i < 30'000'000; ++i) x = x + 1e-9 * i;
        p.end_pass();
        p.end_frame();
        return p.passes();
    };
    const auto cpu = run(TimingBackend::CpuTime), wall = run(TimingBackend::CpuFinish);
    ASSERT_EQ(cpu.size(), 2u);
    EXPECT_LT(cpu[0].gpu_ms.median, 10.0) << "a sleep costs no CPU time";
    EXPECT_GT(cpu[1].gpu_ms.median, 2.0 * cpu[0].gpu_ms.median) << "the work does";
    EXPECT_GE(cpu[0].cpu_ms.median, 119.0) << "the recording time is the wall clock";
    EXPECT_GE(wall[0].gpu_ms.median, 119.0) << "finish: the wall clock";
}

TEST(Profiler, ExcludesWarmupFramesFromStatistics) {
    FakeRun run(12);
    auto passes = run.p.passes();
    ASSERT_EQ(passes.size(), 2u);
    EXPECT_EQ(passes[0].name, "shadow");  // first-seen order
    EXPECT_EQ(passes[1].name, "lines");
    // Measured frames 2..11: shadow 3..12 ms.
    EXPECT_EQ(passes[0].gpu_ms.n, 10u);
    EXPECT_DOUBLE_EQ(passes[0].gpu_ms.min, 3);
    EXPECT_DOUBLE_EQ(passes[0].gpu_ms.max, 12);
    EXPECT_DOUBLE_EQ(passes[0].gpu_ms.median, 7.5);
    EXPECT_NEAR(passes[0].gpu_ms.p5, 3.45, 1e-9);
    EXPECT_NEAR(passes[0].gpu_ms.p95, 11.55, 1e-9);
    EXPECT_DOUBLE_EQ(passes[1].gpu_ms.median, 2);
    EXPECT_DOUBLE_EQ(passes[1].stats.at("segments"), 1000 + 6.5);  // mean of 1002..1011
    Profiler::Stats frame = run.p.frame_ms();
    EXPECT_EQ(frame.n, 10u);
    EXPECT_DOUBLE_EQ(frame.median, 7.5 + 0.5 + 2);
}

TEST(Profiler, PassRunTwiceInAFrameCountsItsTotal) {
    double t = 0;
    Profiler p;
    p.set_clock([&] { return t; });
    p.set_warmup_frames(0);
    p.init(TimingBackend::CpuFinish, "llvmpipe");
    p.begin_frame(0);
    for (int i = 0; i < 2; ++i) {
        p.begin_pass("blur");
        t += 3;
        p.end_pass();
    }
    p.end_frame();
    auto passes = p.passes();
    ASSERT_EQ(passes.size(), 1u);
    EXPECT_EQ(passes[0].gpu_ms.n, 1u);
    EXPECT_DOUBLE_EQ(passes[0].gpu_ms.median, 6);
}

TEST(Profiler, MisuseThrowsLogicError) {
    Profiler p;
    p.init(TimingBackend::CpuFinish, "llvmpipe");
    EXPECT_THROW(p.begin_pass("x"), std::logic_error);
    EXPECT_THROW(p.end_frame(), std::logic_error);
    p.begin_frame(0);
    EXPECT_THROW(p.begin_frame(1), std::logic_error);
    p.begin_pass("open");
    EXPECT_THROW(p.end_frame(), std::logic_error);
    p.end_pass();
    EXPECT_THROW(p.end_pass(), std::logic_error);
    p.end_frame();
}

}  // namespace
}  // namespace pathlet
