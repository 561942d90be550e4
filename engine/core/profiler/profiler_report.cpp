// Reporting side of the profiler: statistics over measured frames, text table, CSV, JSON
// and a Chrome/Perfetto trace. Warm-up frames are left out of every statistic (they still
// appear in the trace, marked, because JIT stalls are worth seeing).
#include "profiler/profiler.hpp"
#include "util/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace pathlet {

namespace {

using json = nlohmann::json;

json stats_json(const Profiler::Stats& s) {
    return {{"median", s.median}, {"p5", s.p5}, {"p95", s.p95}, {"mean", s.mean},
            {"min", s.min},       {"max", s.max}, {"n", s.n}};
}

// Share of the frame by medians, so a table's column adds up the way it reads.
double share_pct(const Profiler::Stats& pass, const Profiler::Stats& frame) {
    return frame.median > 0 ? 100.0 * pass.median / frame.median : 0.0;
}

double fps(const Profiler::Stats& frame) { return frame.median > 0 ? 1000.0 / frame.median : 0.0; }

std::string fmt(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

using text::csv_field;

int64_t to_us(double ms) { return int64_t(std::llround(ms * 1000.0)); }

size_t warmup_count(const std::vector<Profiler::FrameRecord>& frames) {
    return size_t(std::count_if(frames.begin(), frames.end(), [](const auto& f) { return f.warmup; }));
}

}  // namespace

std::vector<Profiler::PassResult> Profiler::passes() const {
    std::vector<std::vector<double>> gpu(pass_names_.size()), cpu(pass_names_.size());
    for (const FrameRecord& f : frames_) {
        if (!measured(f) || !f.cpu.valid) continue;
        // A pass run twice in a frame counts once, with its total: shares stay per frame.
        std::vector<double> g(pass_names_.size(), 0), c(pass_names_.size(), 0);
        std::vector<char> seen(pass_names_.size(), 0), gpu_ok(pass_names_.size(), 1);
        for (const PassSample& s : f.passes) {
            size_t p = size_t(s.pass);
            seen[p] = 1;
            c[p] += s.cpu.duration();
            if (s.gpu.valid) g[p] += s.gpu.duration();
            else gpu_ok[p] = 0;
        }
        for (size_t p = 0; p < pass_names_.size(); ++p) {
            if (!seen[p]) continue;
            cpu[p].push_back(c[p]);
            if (gpu_ok[p]) gpu[p].push_back(g[p]);
        }
    }
    std::vector<PassResult> out;
    for (size_t p = 0; p < pass_names_.size(); ++p) {
        PassResult r;
        r.name = pass_names_[p];
        r.gpu_ms = compute_stats(gpu[p]);
        r.cpu_ms = compute_stats(cpu[p]);
        if (auto it = stats_.find(int(p)); it != stats_.end())
            for (const auto& [name, a] : it->second) r.stats[name] = a.n ? a.sum / double(a.n) : 0.0;
        out.push_back(std::move(r));
    }
    return out;
}

Profiler::Stats Profiler::frame_ms() const {
    std::vector<double> v;
    for (const FrameRecord& f : frames_)
        if (measured(f) && f.gpu.valid) v.push_back(f.gpu.duration());
    return compute_stats(std::move(v));
}

Profiler::Stats Profiler::frame_cpu_ms() const {
    std::vector<double> v;
    for (const FrameRecord& f : frames_)
        if (measured(f) && f.cpu.valid) v.push_back(f.cpu.duration());
    return compute_stats(std::move(v));
}

std::string Profiler::table(const std::string& title) const {
    const auto results = passes();
    const Stats frame = frame_ms();
    const size_t warm = warmup_count(frames_);

    size_t w = 24;
    for (size_t p = 0; p < pass_names_.size(); ++p) w = std::max(w, pass_names_[p].size() + 2 * size_t(pass_depth_[p]) + 2);
    auto name_col = [&](const std::string& s) { return s + std::string(w > s.size() ? w - s.size() : 1, ' '); };
    auto row = [&](const std::string& name, const Stats& g, const std::string& share, const Stats& c) {
        return name_col(name) + fmt("%10.3f", g.median) + fmt("%10.3f", g.p5) + fmt("%10.3f", g.p95) + share +
               fmt("%10.3f", c.median) + "\n";
    };

    std::ostringstream out;
    out << title << "\n";
    out << "timing: " << description_ << "\n";
    out << "frames: " << frame.n << " measured, " << warm << " warm-up excluded";
    if (dropped_) out << ", " << dropped_ << " GPU results dropped";
    out << "\n";
    out << name_col("pass") << "    median        p5       p95     share   cpu med\n";
    out << name_col("") << "      (ms)      (ms)      (ms)       (%)      (ms)\n";
    for (size_t p = 0; p < results.size(); ++p) {
        const PassResult& r = results[p];
        out << row(std::string(2 * size_t(pass_depth_[p]), ' ') + r.name, r.gpu_ms,
                   fmt("%9.1f%%", share_pct(r.gpu_ms, frame)), r.cpu_ms);
    }
    out << row("frame", frame, fmt("%9.1f%%", frame.n ? 100.0 : 0.0), frame_cpu_ms());
    out << name_col("fps (median frame)") << fmt("%10.1f", fps(frame)) << "\n";
    out << name_col("fps (wall clock)") << fmt("%10.1f", wall_fps()) << "\n";
    if (backend_ == TimingBackend::GlTimestamp && unstable(frame))  // a GPU's clocks; a shared CPU's spread says nothing
        out << "UNSTABLE: frame times p95/p5 = " << fmt("%.2f", frame.p95 / frame.p5) << " > " << fmt("%.1f", kUnstableRatio)
            << " (a clock that changed during the run, or other load): quote the range, not the median\n";
    // What passes counted (segments drawn, OIT nodes, overflow events...), mean per frame.
    bool header = false;
    for (const PassResult& r : results) {
        if (r.stats.empty()) continue;
        if (!header) out << "stats (mean per measured frame):\n", header = true;
        std::string line = "  " + r.name + ":";
        for (const auto& [k, v] : r.stats) line += " " + k + " " + fmt("%.6g", v) + ",";
        line.pop_back();
        out << line << "\n";
    }
    return out.str();
}

std::string Profiler::csv() const {
    std::ostringstream out;
    out << "kind,name,depth,n,median_ms,p5_ms,p95_ms,mean_ms,min_ms,max_ms,"
           "cpu_n,cpu_median_ms,cpu_p5_ms,cpu_p95_ms,cpu_mean_ms,cpu_min_ms,cpu_max_ms,share_pct,stats\n";
    auto stats_cols = [&](const Stats& s) {
        return std::to_string(s.n) + "," + fmt("%.6f", s.median) + "," + fmt("%.6f", s.p5) + "," +
               fmt("%.6f", s.p95) + "," + fmt("%.6f", s.mean) + "," + fmt("%.6f", s.min) + "," + fmt("%.6f", s.max);
    };
    const Stats frame = frame_ms();
    const auto results = passes();
    for (size_t p = 0; p < results.size(); ++p) {
        const PassResult& r = results[p];
        std::string extra;
        for (const auto& [k, v] : r.stats) extra += (extra.empty() ? "" : ";") + k + "=" + fmt("%g", v);
        out << "pass," << csv_field(r.name) << "," << pass_depth_[p] << "," << stats_cols(r.gpu_ms) << ","
            << stats_cols(r.cpu_ms) << "," << fmt("%.3f", share_pct(r.gpu_ms, frame)) << "," << csv_field(extra)
            << "\n";
    }
    out << "frame,frame,0," << stats_cols(frame) << "," << stats_cols(frame_cpu_ms()) << ","
        << (frame.n ? "100.000" : "0.000") << ",\n";
    return out.str();
}

nlohmann::json Profiler::to_json(const nlohmann::json& meta) const {
    const Stats frame = frame_ms();
    const size_t warm = warmup_count(frames_);
    json pass_list = json::array();
    const auto results = passes();
    for (size_t p = 0; p < results.size(); ++p) {
        const PassResult& r = results[p];
        pass_list.push_back({{"name", r.name},
                          {"depth", pass_depth_[p]},
                          {"gpu_ms", stats_json(r.gpu_ms)},
                          {"cpu_ms", stats_json(r.cpu_ms)},
                          {"share_pct", share_pct(r.gpu_ms, frame)},
                          {"stats", r.stats}});
    }
    return {{"meta", meta},
            {"timing",
             {{"backend", to_string(backend_)},
              {"description", description_},
              {"warmup_frames_excluded", warm},
              {"frames_measured", frame.n},
              {"warmup_seconds", warmup_seconds_},
              {"warmup_settled", warmup_settled_},
              {"gpu_frames_dropped", dropped_}}},
            {"frame",
             {{"gpu_ms", stats_json(frame)},
              {"cpu_ms", stats_json(frame_cpu_ms())},
              {"fps", fps(frame)},
              {"wall_fps", wall_fps()},
              {"p95_over_p5", frame.p5 > 0 ? frame.p95 / frame.p5 : 0.0},
              {"unstable", unstable(frame)}}},
            {"passes", pass_list}};
}

nlohmann::json Profiler::chrome_trace() const {
    constexpr int kPid = 1, kCpuTrack = 1, kGpuTrack = 2;
    json events = json::array();
    auto meta_event = [&](const char* what, int tid, const std::string& name) {
        json e = {{"ph", "M"}, {"pid", kPid}, {"name", what}, {"args", {{"name", name}}}};
        if (tid) e["tid"] = tid;
        events.push_back(e);
    };
    meta_event("process_name", 0, "pathlet");
    meta_event("thread_name", kCpuTrack, "CPU (command recording)");
    meta_event("thread_name", kGpuTrack, "GPU: " + description_);

    auto x_event = [&](const std::string& name, const char* cat, int tid, const Interval& iv, json args) {
        if (!iv.valid) return;
        events.push_back({{"name", name}, {"cat", cat}, {"ph", "X"}, {"pid", kPid}, {"tid", tid},
                          {"ts", to_us(iv.begin)}, {"dur", std::max<int64_t>(0, to_us(iv.end) - to_us(iv.begin))},
                          {"args", std::move(args)}});
    };
    for (const FrameRecord& f : frames_) {
        json args = {{"frame", f.index}, {"warmup", f.warmup}};
        const std::string name = "frame " + std::to_string(f.index);
        x_event(name, "frame", kCpuTrack, f.cpu, args);
        x_event(name, "frame", kGpuTrack, f.gpu, args);
        for (const PassSample& s : f.passes) {
            const std::string& pass = pass_names_[size_t(s.pass)];
            x_event(pass, "pass", kCpuTrack, s.cpu, args);
            x_event(pass, "pass", kGpuTrack, s.gpu, args);
        }
    }
    return {{"traceEvents", events},
            {"displayTimeUnit", "ms"},
            {"otherData", {{"backend", to_string(backend_)}, {"description", description_}}}};
}

}  // namespace pathlet
