// Progress for long frame sequences, always on stderr (stdout may carry JSON or frames).
// On a terminal: one line redrawn with '\r' at most ~10 times a second. Elsewhere (CI logs):
// a plain line every max(1, total/20) items or every 5 s. NO_COLOR turns colour off. The rate
// is items over the wall clock since the Progress was made: make it when the work starts (the
// render command makes it at the renderer's first report, 0 frames, before the first frame).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace pathlet {

// "0.4s", "45s", "2m08s", "1h02m"; "--" for negative or non-finite values.
std::string format_duration(double seconds);

class Progress {
public:
    // counts = false: the work reports fractions (total is a scale), so show percent and ETA
    // only, not "n/total" and a rate.
    Progress(std::string what, size_t total, bool quiet = false, bool counts = true);
    ~Progress();  // ends a half-drawn terminal line if finish() was never called
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void update(size_t done, const std::string& note = "");
    void finish(const std::string& summary);  // "<summary> in 2m08s (3.4 fps (wall clock))"
    // With the rate a better clock measured (the profiler's wall clock of the frame loop), so
    // the last line says what the summary table says.
    void finish(const std::string& summary, double rate);

private:
    using Clock = std::chrono::steady_clock;
    double elapsed_s() const;
    std::string status(size_t done, const std::string& note) const;  // "12/450 frames  3.4 fps  ETA ..."
    std::string bar(size_t done) const;
    std::string rate_unit() const;  // "fps (wall clock)" for frames, else "<what>/s"
    void emit(const std::string& text);

    std::string what_;
    size_t total_;
    bool quiet_, tty_, colour_, counts_;
    Clock::time_point start_, last_print_;
    size_t last_done_ = 0, done_ = 0;
    size_t step_;
    bool line_open_ = false;  // a '\r' line is on screen
    bool finished_ = false;
};

}  // namespace pathlet
