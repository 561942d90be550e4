// Shape of the profiler's reports: table, CSV, JSON and the Chrome/Perfetto trace.
#include "fake_profile.hpp"

#include "text_lines.hpp"

#include <gtest/gtest.h>

#include <map>
#include <sstream>

namespace pathlet {
namespace {

using test::lines_of;

TEST(ProfilerReport, TableListsPassesInOrderWithFrameAndFps) {
    FakeRun run(12);
    const std::string table = run.p.table("Table 3: lineao @ 256x256");
    auto lines = lines_of(table);
    ASSERT_GE(lines.size(), 8u) << table;
    EXPECT_EQ(lines[0], "Table 3: lineao @ 256x256");
    EXPECT_NE(table.find("glFinish-bracketed CPU clock (llvmpipe"), std::string::npos) << table;
    EXPECT_NE(table.find("10 measured, 2 warm-up excluded"), std::string::npos) << table;
    const size_t shadow = table.find("\nshadow "), lines_row = table.find("\nlines "), frame = table.find("\nframe ");
    ASSERT_NE(shadow, std::string::npos) << table;
    EXPECT_LT(shadow, lines_row);
    EXPECT_LT(lines_row, frame);
    // shadow: median 7.5 of a 10 ms median frame -> 75.0 %; fps = 1000 / 10.
    EXPECT_NE(table.find("7.500"), std::string::npos) << table;
    EXPECT_NE(table.find("75.0%"), std::string::npos) << table;
    EXPECT_NE(table.find("100.0"), std::string::npos) << table;
    EXPECT_NE(table.find("fps"), std::string::npos) << table;
}

TEST(ProfilerReport, CsvHasOneRowPerPassPlusFrame) {
    FakeRun run(12);
    auto lines = lines_of(run.p.csv());
    ASSERT_EQ(lines.size(), 4u);  // header, shadow, lines, frame
    EXPECT_EQ(lines[0].rfind("kind,name,depth,n,median_ms,p5_ms,p95_ms,mean_ms,min_ms,max_ms,cpu_n,", 0), 0u);
    EXPECT_EQ(lines[1].rfind("pass,shadow,0,10,7.500000,3.450000,11.550000,", 0), 0u) << lines[1];
    EXPECT_EQ(lines[2].rfind("pass,lines,0,10,2.000000,", 0), 0u) << lines[2];
    EXPECT_NE(lines[2].find("segments=1006.5"), std::string::npos) << lines[2];
    EXPECT_EQ(lines[3].rfind("frame,frame,0,10,10.000000,", 0), 0u) << lines[3];
    const auto columns = [](const std::string& l) { return std::count(l.begin(), l.end(), ','); };
    for (const auto& l : lines) EXPECT_EQ(columns(l), columns(lines[0])) << l;
}

TEST(ProfilerReport, JsonCarriesMetaBackendAndStats) {
    FakeRun run(12);
    nlohmann::json meta = {{"renderer", "llvmpipe"}, {"graph", "lineao"}, {"size", {256, 256}}};
    nlohmann::json j = run.p.to_json(meta);
    EXPECT_EQ(j["meta"], meta);
    EXPECT_EQ(j["timing"]["backend"], "finish");
    EXPECT_EQ(j["timing"]["warmup_frames_excluded"], 2);
    EXPECT_EQ(j["timing"]["frames_measured"], 10);
    EXPECT_DOUBLE_EQ(j["frame"]["gpu_ms"]["median"].get<double>(), 10.0);
    EXPECT_DOUBLE_EQ(j["frame"]["fps"].get<double>(), 100.0);
    ASSERT_EQ(j["passes"].size(), 2u);
    EXPECT_EQ(j["passes"][0]["name"], "shadow");
    EXPECT_NEAR(j["passes"][0]["gpu_ms"]["p95"].get<double>(), 11.55, 1e-9);
    EXPECT_DOUBLE_EQ(j["passes"][0]["share_pct"].get<double>(), 75.0);
    EXPECT_DOUBLE_EQ(j["passes"][1]["stats"]["segments"].get<double>(), 1006.5);
    // Round-trips through text (no NaN/inf that would break JSON consumers).
    EXPECT_EQ(nlohmann::json::parse(j.dump()), j);
}

TEST(ProfilerReport, ChromeTraceHasNestedXEventsOnBothTracks) {
    FakeRun run(5);
    nlohmann::json trace = nlohmann::json::parse(run.p.chrome_trace().dump());  // valid JSON text
    ASSERT_TRUE(trace.contains("traceEvents"));
    std::map<int, std::string> track_names;
    std::map<std::pair<int, uint64_t>, int64_t> frame_dur, pass_sum;  // (tid, frame) -> µs
    size_t x_events = 0;
    for (const auto& e : trace["traceEvents"]) {
        if (e["ph"] == "M" && e["name"] == "thread_name") track_names[e["tid"].get<int>()] = e["args"]["name"];
        if (e["ph"] != "X") continue;
        ++x_events;
        ASSERT_TRUE(e.contains("ts") && e.contains("dur") && e.contains("pid") && e.contains("tid")) << e;
        EXPECT_GE(e["dur"].get<int64_t>(), 0);
        auto key = std::make_pair(e["tid"].get<int>(), e["args"]["frame"].get<uint64_t>());
        if (e["cat"] == "frame") frame_dur[key] = e["dur"];
        else {
            EXPECT_TRUE(e["name"] == "shadow" || e["name"] == "lines") << e;
            pass_sum[key] += e["dur"].get<int64_t>();
        }
    }
    ASSERT_EQ(track_names.size(), 2u);
    EXPECT_NE(track_names[2].find("glFinish"), std::string::npos);
    EXPECT_EQ(x_events, 5u * 3u * 2u);  // (frame + 2 passes) x 2 tracks
    for (const auto& [key, sum] : pass_sum) {
        EXPECT_LE(sum, frame_dur[key]) << "track " << key.first << " frame " << key.second;
        EXPECT_GE(sum, frame_dur[key] - 600) << "only the 0.5 ms gap is outside passes";
    }
    // Frame 3 (measured): shadow 4 ms + gap 0.5 + lines 2 = 6.5 ms = 6500 µs.
    EXPECT_EQ(frame_dur[std::make_pair(2, uint64_t(3))], 6500);
}


// Wall clock over the measured frames: from the first measured frame's start to the flush that
// saw the last one done. FakeRun's measured frames k = 2..9 each take 13.5 + k ms of the clock,
// gaps included (the flush comes after the last gap): 152 ms for 8 frames.
TEST(ProfilerReport, WallFpsSpansTheMeasuredFramesToTheFlush) {
    FakeRun r(10);
    EXPECT_EQ(r.p.wall_fps(), 0.0);  // not flushed yet: no end
    r.p.flush();
    EXPECT_NEAR(r.p.wall_fps(), 8 * 1000.0 / 152.0, 1e-9);
    r.t += 1000;  // a later flush does not move the end
    r.p.flush();
    EXPECT_NEAR(r.p.wall_fps(), 8 * 1000.0 / 152.0, 1e-9);
    EXPECT_NE(r.p.table("t").find("fps (wall clock)"), std::string::npos);
    const auto j = r.p.to_json({});
    EXPECT_NEAR(j["frame"]["wall_fps"].get<double>(), 8 * 1000.0 / 152.0, 1e-9);
}

// A run whose frame times spread beyond p95/p5 = 1.5 is flagged in the JSON; a steady one is not.
// The table says UNSTABLE only for a GPU's timestamps (a clock that changed): on llvmpipe's
// finish-bracketed clocks a spread is the shared CPU's load, and the README promises the word
// for GPUs only.
TEST(ProfilerReport, UnstableRunsAreFlaggedInTableAndJson) {
    FakeRun spread(10);  // frames 7.5 .. 14.5 ms: p95/p5 ~ 1.8
    spread.p.flush();
    EXPECT_TRUE(spread.p.unstable());
    EXPECT_EQ(spread.p.backend(), TimingBackend::CpuFinish);
    EXPECT_EQ(spread.p.table("t").find("UNSTABLE"), std::string::npos);
    EXPECT_TRUE(spread.p.to_json({})["frame"]["unstable"].get<bool>());

    Profiler steady;
    double t = 0;
    steady.set_clock([&] { return t; });
    steady.set_warmup_frames(0);
    steady.init(TimingBackend::CpuFinish, "llvmpipe");
    for (int k = 0; k < 20; ++k) {
        steady.begin_frame(uint64_t(k));
        steady.begin_pass("lines");
        t += k % 2 ? 10.0 : 12.0;  // within 1.5x
        steady.end_pass();
        steady.end_frame();
    }
    steady.flush();
    EXPECT_FALSE(steady.unstable());
    EXPECT_EQ(steady.table("t").find("UNSTABLE"), std::string::npos);
    EXPECT_FALSE(steady.to_json({})["frame"]["unstable"].get<bool>());
    EXPECT_NEAR(steady.to_json({})["frame"]["p95_over_p5"].get<double>(), 1.2, 1e-9);
}

}  // namespace
}  // namespace pathlet
