// gtest's side of tests/support/optional_tool.sh, the one decision for a test that needs an
// optional tool: PATHLET_REQUIRE_TOOLS("ffmpeg ffprobe") returns from the test as skipped
// (outside CI) or failed (CI set) with the script's message when one is not on PATH.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace pathlet::test {

struct ToolCheck {
    int status = 0;       // 0: every tool is there, 77: skip, else fail
    std::string message;  // the script's line when one is missing
};

// `tools`: space-separated names, or "--missing 'WHY'" for the decision alone.
inline ToolCheck check_tools(const std::string& tools) {
    ToolCheck c;
    const std::string cmd = "bash '" PATHLET_SOURCE_DIR "/tests/support/optional_tool.sh' " + tools + " 2>&1";
    FILE* p = ::popen(cmd.c_str(), "r");
    if (!p) return {1, "cannot run " + cmd};
    char buf[512];
    while (std::fgets(buf, sizeof buf, p)) c.message += buf;
    const int status = ::pclose(p);
    c.status = WIFEXITED(status) ? WEXITSTATUS(status) : 1;
    return c;
}

}  // namespace pathlet::test

#define PATHLET_REQUIRE_TOOLS(tools)                                         \
    do {                                                                     \
        const ::pathlet::test::ToolCheck check_ = ::pathlet::test::check_tools(tools); \
        if (check_.status == 77) GTEST_SKIP() << check_.message;             \
        if (check_.status != 0) FAIL() << check_.message;                    \
    } while (0)
