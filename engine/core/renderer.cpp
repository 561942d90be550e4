#include "renderer.hpp"

#include "render_job.hpp"

#include "util/atomic_file.hpp"

#include "executor.hpp"
#include "formats.hpp"
#include "frames/async_output.hpp"
#include "image_io.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

namespace fs = std::filesystem;

namespace pathlet {

std::vector<double> TimeRange::times() const {
    std::vector<double> t;
    if (!(step > 0) || end <= start) return {start};
    size_t n = size_t(std::floor((end - start) / step + 1e-9)) + 1;
    for (size_t i = 0; i < n; ++i) t.push_back(start + double(i) * step);
    return t;
}

TimeRange default_time_range(const Scene& scene) {
    if (scene.lines.timeless) return {0, 0, 0.25};
    return {scene.lines.time_min(), scene.lines.time_max(), 0.25};
}

TimeRange default_bench_time(const Scene& scene) {
    if (scene.lines.timeless) return {0, 0, 0};
    const double mid = 0.5 * (scene.lines.time_min() + scene.lines.time_max());
    return {mid, mid, 0};
}

TimeRange default_quality_time(const Scene& scene) {
    constexpr double kStep = 0.04, kSpan = 10 * kStep;  // 11 frames
    const double t0 = scene.lines.timeless ? 0.0 : scene.lines.time_min();
    const double t1 = scene.lines.timeless ? 0.0 : scene.lines.time_max();
    if (t1 - t0 < kSpan) return {t0, t1, t1 > t0 ? (t1 - t0) / 10 : kStep};
    const double start = std::min(0.5 * (t0 + t1), t1 - kSpan);
    return {start, start + kSpan, kStep};
}

std::string picked_time_note(const TimeRange& t, const Scene& scene, const std::string& how) {
    char b[256];
    const std::vector<double> times = t.times();
    if (times.size() == 1)
        std::snprintf(b, sizeof b, "time %g s", t.start);
    else
        std::snprintf(b, sizeof b, "time %g..%g s (%zu frames)", t.start, times.back(), times.size());
    std::string s = b;
    if (scene.lines.timeless) return s + " (" + scene.source + " has no time)";
    std::snprintf(b, sizeof b, "%g..%g s", scene.lines.time_min(), scene.lines.time_max());
    return s + " (" + how + " of " + scene.source + "'s " + b + ", as no time was given)";
}

TimeRange parse_time_range(const std::string& text) {
    std::vector<double> parts;
    size_t pos = 0;
    try {
        while (pos <= text.size()) {
            size_t c = text.find(':', pos);
            std::string tok = text.substr(pos, c == std::string::npos ? std::string::npos : c - pos);
            size_t used = 0;
            parts.push_back(std::stod(tok, &used));
            if (used != tok.size()) throw std::invalid_argument("");
            if (c == std::string::npos) break;
            pos = c + 1;
        }
    } catch (const std::exception&) {
        throw std::invalid_argument("--time '" + text + "': expected T, START:END or START:END:STEP in seconds (e.g. 0:18:0.04)");
    }
    TimeRange r;
    if (parts.size() == 1) {
        r.start = r.end = parts[0];
    } else if (parts.size() == 2 || parts.size() == 3) {
        r.start = parts[0];
        r.end = parts[1];
        r.step = parts.size() == 3 ? parts[2] : 0.04;
        if (!(r.step > 0)) throw std::invalid_argument("--time '" + text + "': the step must be positive");
        if (r.end < r.start) throw std::invalid_argument("--time '" + text + "': END is before START");
    } else {
        throw std::invalid_argument("--time '" + text + "': expected T, START:END or START:END:STEP");
    }
    return r;
}

glm::ivec2 parse_size(const std::string& text) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 1 || h < 1 ||
        w > 16384 || h > 16384)
        throw std::invalid_argument("--size '" + text + "': expected WIDTHxHEIGHT, e.g. 1280x720 (1..16384)");
    return {w, h};
}

void check_render_limits(const RenderOptions& opt) {
    if (opt.ssaa < 1 || opt.ssaa > 8) throw std::invalid_argument("ssaa must be 1..8 (got " + std::to_string(opt.ssaa) + ")");
    if (opt.size.x * opt.ssaa > 16384 || opt.size.y * opt.ssaa > 16384)
        throw std::invalid_argument("ssaa x size exceeds 16384 pixels on a side (" + std::to_string(opt.size.x) + "x" +
                                    std::to_string(opt.size.y) + " x " + std::to_string(opt.ssaa) + "); lower one of them");
    if (opt.warmup < 0) throw std::invalid_argument("warmup must be >= 0 (got " + std::to_string(opt.warmup) + ")");
}

std::string graph_display_name(const GraphFile& g) {
    return g.name.empty() ? fs::path(g.path).stem().string() : g.name;
}

std::string resolve_graph_path(const std::string& arg) { return find_graph_file(arg); }

std::string incomplete_frames_line(const RenderResult& r) {
    if (r.incomplete_frames.empty()) return "";
    std::string list;
    for (size_t f : r.incomplete_frames) list += (list.empty() ? "" : ", ") + std::to_string(f);
    return "incomplete frames: " + std::to_string(r.incomplete_frames.size()) + " of " + std::to_string(r.frames) +
           " (" + list + ")";
}

RenderResult render(Runtime& rt, const Scene& scene, const RenderOptions& opt,
                    const std::function<void(const Executor&, size_t)>& on_frame) {
    return RenderJob(rt, opt).run(scene, on_frame);
}

}  // namespace pathlet
