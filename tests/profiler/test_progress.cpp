// Progress off a terminal (CI logs): plain lines, no '\r', no colour, on stderr only.
#include "common/progress.hpp"

#include "text_lines.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace pathlet {
namespace {

using test::lines_of;

TEST(FormatDuration, PicksUnitsByMagnitude) {
    EXPECT_EQ(format_duration(0.42), "0.4s");
    EXPECT_EQ(format_duration(45), "45s");
    EXPECT_EQ(format_duration(128), "2m08s");
    EXPECT_EQ(format_duration(3720), "1h02m");
    EXPECT_EQ(format_duration(-1), "--");
    EXPECT_EQ(format_duration(1.0 / 0.0), "--");
}

TEST(Progress, PlainLinesEveryTwentiethWhenNotATerminal) {
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();  // a file, so isatty(stderr) is false
    {
        Progress p("frames", 40);
        for (size_t i = 1; i <= 40; ++i) p.update(i, i == 40 ? "lineao" : "");
        p.finish("40 frames written");
    }
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(testing::internal::GetCapturedStdout(), "") << "progress must never touch stdout";
    auto lines = lines_of(err);
    ASSERT_EQ(lines.size(), 21u) << err;  // every 2nd frame (40/20), plus the summary
    EXPECT_EQ(lines[0].rfind("2/40 frames  ", 0), 0u) << lines[0];
    EXPECT_NE(lines[0].find(" fps (wall clock)  ETA "), std::string::npos) << lines[0];
    EXPECT_NE(lines[0].find("(5%)"), std::string::npos) << lines[0];
    EXPECT_EQ(lines[19].rfind("40/40 frames  ", 0), 0u) << lines[19];
    EXPECT_NE(lines[19].find("lineao"), std::string::npos);
    EXPECT_EQ(lines[19].find("ETA"), std::string::npos) << "no ETA once done";
    EXPECT_EQ(lines[20].rfind("40 frames written in ", 0), 0u) << lines[20];
    EXPECT_EQ(err.find('\r'), std::string::npos);
    EXPECT_EQ(err.find('\033'), std::string::npos);
}

TEST(Progress, SmallTotalsReportEveryItem) {
    testing::internal::CaptureStderr();
    {
        Progress p("images", 3);
        for (size_t i = 1; i <= 3; ++i) p.update(i);
    }
    auto lines = lines_of(testing::internal::GetCapturedStderr());
    ASSERT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[2].rfind("3/3 images  ", 0), 0u) << lines[2];
    EXPECT_NE(lines[2].find("images/s"), std::string::npos) << lines[2];
}

TEST(Progress, QuietPrintsNothing) {
    testing::internal::CaptureStderr();
    {
        Progress p("frames", 10, /*quiet=*/true);
        for (size_t i = 1; i <= 10; ++i) p.update(i);
        p.finish("done");
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

}  // namespace
}  // namespace pathlet
