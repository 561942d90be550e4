// Progress on stderr for the CLI: a single line rewritten with \r on a terminal, plain
// lines (at most one per 10 %) when stderr is a file or pipe.
#pragma once

#include "progress.hpp"

#include <chrono>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace pathlet::trace {

class ProgressPrinter {
public:
    explicit ProgressPrinter(std::string prefix) : prefix_(std::move(prefix)), tty_(isatty(fileno(stderr)) != 0) {}
    ~ProgressPrinter() { done(); }

    Progress callback() {
        return [this](double f, std::string_view stage) { update(f, stage); };
    }
    void update(double f, std::string_view stage) {
        const int pct = int(f * 100.0 + 0.5);
        if (tty_) {
            std::fprintf(stderr, "\r%s: %.*s %3d%%   ", prefix_.c_str(), int(stage.size()), stage.data(), pct);
            std::fflush(stderr);
            open_ = true;
        } else if (stage != last_stage_ || pct / 10 != last_pct_ / 10) {
            std::fprintf(stderr, "%s: %.*s %d%%\n", prefix_.c_str(), int(stage.size()), stage.data(), pct);
        }
        last_stage_ = stage;
        last_pct_ = pct;
    }
    void done() {
        if (open_) std::fputc('\n', stderr);
        open_ = false;
    }
    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

private:
    std::string prefix_;
    bool tty_, open_ = false;
    std::string last_stage_;
    int last_pct_ = -100;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace pathlet::trace
