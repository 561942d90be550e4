// The summary a bench ends with: a wall-fps column beside the frame times, and runs whose frame
// times spread beyond p95/p5 = 1.5 marked UNSTABLE with a line that says what to do about it.
#include "bench/report.hpp"

#include <gtest/gtest.h>

using namespace pathlet;
using namespace pathlet::cli::bench;

namespace {
Profiler::Stats frame(double median, double p5, double p95) {
    Profiler::Stats s;
    s.median = median;
    s.p5 = p5;
    s.p95 = p95;
    s.n = 100;
    return s;
}
std::string line_of(const std::string& text, const std::string& start) {
    const size_t at = text.find(start);
    return at == std::string::npos ? "" : text.substr(at, text.find('\n', at) - at);
}
}  // namespace

TEST(BenchSummary, HasWallFpsAndMarksOnlyTheUnstableRun) {
    const std::string t = summary_table({{"steady  1920x1080", frame(4.0, 3.9, 4.2), 240.5, "10+2 / 5 / 1"},
                                         {"governed  1920x1080", frame(20.0, 4.0, 74.0), 31.0}});
    EXPECT_NE(t.find("wall fps"), std::string::npos) << t;
    const std::string steady = line_of(t, "  steady"), governed = line_of(t, "  governed");
    EXPECT_NE(steady.find("240.5"), std::string::npos) << steady;
    EXPECT_NE(steady.find("250.0"), std::string::npos) << steady;  // fps of the median frame
    EXPECT_EQ(steady.find("UNSTABLE"), std::string::npos) << steady;
    EXPECT_NE(governed.find("UNSTABLE"), std::string::npos) << governed;
    EXPECT_NE(t.find("UNSTABLE: frame times spread more than p95/p5 = 1.5"), std::string::npos) << t;
}

// llvmpipe's frames are timed by CPU clocks and it has no clock governor: a spread there is
// other load, not a clock, and the README promises UNSTABLE for GPUs only.
TEST(BenchSummary, NoUnstableOnASoftwareRasterizer) {
    SummaryRow spread{"llvmpipe  160x90", frame(20.0, 4.0, 74.0), 31.0};
    spread.gpu_timing = false;
    const std::string t = summary_table({spread});
    EXPECT_EQ(t.find("UNSTABLE"), std::string::npos) << t;
    EXPECT_NE(t.find("frame fps"), std::string::npos) << t;
}

TEST(BenchSummary, NoUnstableNoteWhenEveryRunIsSteady) {
    const std::string t = summary_table({{"a", frame(10, 9.5, 11), 95.0}});
    EXPECT_EQ(t.find("UNSTABLE"), std::string::npos) << t;
}
