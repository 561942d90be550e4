#include "common/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unistd.h>

namespace pathlet {

namespace {

constexpr double kTtyInterval = 0.1;   // seconds between redraws (~10 Hz)
constexpr double kPlainInterval = 5.0; // seconds between plain lines at the latest
constexpr int kBarWidth = 20;

std::string printf_string(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

bool colour_allowed() {
    const char* no_color = std::getenv("NO_COLOR");  // https://no-color.org: any non-empty value
    const char* term = std::getenv("TERM");
    return !(no_color && *no_color) && !(term && std::strcmp(term, "dumb") == 0);
}

}  // namespace

std::string format_duration(double s) {
    if (!std::isfinite(s) || s < 0) return "--";
    if (s < 10) return printf_string("%.1fs", s);
    long total = std::lround(s);
    if (total < 60) return std::to_string(total) + "s";
    char buf[32];
    if (total < 3600) std::snprintf(buf, sizeof buf, "%ldm%02lds", total / 60, total % 60);
    else std::snprintf(buf, sizeof buf, "%ldh%02ldm", total / 3600, (total % 3600) / 60);
    return buf;
}

Progress::Progress(std::string what, size_t total, bool quiet, bool counts)
    : what_(std::move(what)),
      total_(total),
      quiet_(quiet),
      tty_(::isatty(STDERR_FILENO) == 1),
      colour_(tty_ && colour_allowed()),
      counts_(counts),
      start_(Clock::now()),
      last_print_(start_),
      step_(std::max<size_t>(1, total / 20)) {}

Progress::~Progress() {
    if (line_open_) emit("\n");
}

double Progress::elapsed_s() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

std::string Progress::status(size_t done, const std::string& note) const {
    double t = elapsed_s();
    double rate = t > 0 ? double(done) / t : 0;
    std::string s;
    if (counts_) {
        s = std::to_string(done) + "/" + std::to_string(total_) + " " + what_;
        s += "  " + printf_string("%.1f", rate) + " " + rate_unit();
    } else {
        s = what_ + " " + std::to_string(total_ ? done * 100 / total_ : 100) + "%";
    }
    if (done < total_) s += "  ETA " + format_duration(rate > 0 ? double(total_ - done) / rate : -1);
    if (!note.empty()) s += "  " + note;
    return s;
}

std::string Progress::rate_unit() const { return what_ == "frames" ? "fps (wall clock)" : what_ + "/s"; }

std::string Progress::bar(size_t done) const {
    int filled = total_ ? int(double(kBarWidth) * double(std::min(done, total_)) / double(total_)) : kBarWidth;
    std::string hashes(size_t(filled), '#'), dots(size_t(kBarWidth - filled), '.');
    if (colour_) hashes = "\033[32m" + hashes + "\033[0m";
    return "[" + hashes + dots + "]";
}

void Progress::emit(const std::string& text) {
    std::fputs(text.c_str(), stderr);
    std::fflush(stderr);
}

void Progress::update(size_t done, const std::string& note) {
    done_ = done;
    if (quiet_) return;
    auto now = Clock::now();
    double since = std::chrono::duration<double>(now - last_print_).count();
    bool last = done >= total_;
    if (tty_) {
        if (!last && since < kTtyInterval) return;
        // "\033[K" clears what a longer previous line left behind.
        // (Appending, not "\r" + string: GCC 12 gives a false -Wrestrict on the latter.)
        std::string line = "\r";
        line += bar(done) + " " + status(done, note) + "\033[K";
        emit(line);
        line_open_ = true;
    } else {
        if (!last && done < last_done_ + step_ && since < kPlainInterval) return;
        if (done == last_done_ && done != 0) return;  // nothing new to say
        size_t pct = total_ ? done * 100 / total_ : 100;
        emit(status(done, note) + (counts_ ? "  (" + std::to_string(pct) + "%)" : std::string()) + "\n");
    }
    last_print_ = now;
    last_done_ = done;
}

void Progress::finish(const std::string& summary) {
    const double t = elapsed_s();
    finish(summary, t > 0 ? double(done_) / t : 0);
}

void Progress::finish(const std::string& summary, double rate) {
    if (finished_) return;
    finished_ = true;
    if (quiet_) return;
    double t = elapsed_s();
    std::string line = summary + " in " + format_duration(t);
    if (counts_) line += " (" + printf_string("%.1f", rate) + " " + rate_unit() + ")";
    line += "\n";
    emit((line_open_ ? "\r\033[K" : "") + line);
    line_open_ = false;
}

}  // namespace pathlet
