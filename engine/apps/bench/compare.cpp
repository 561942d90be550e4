#include "compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

namespace pathlet::cli::bench {
namespace {

using nlohmann::json;

// Passes this short are timer resolution and scheduling noise, whatever their ratio.
constexpr double kMinMs = 0.05;

struct Range {
    double median = 0, p5 = 0, p95 = 0;
    std::vector<double> samples;  // measured frames (not warm-up), where the report has them
};

struct RunTimes {
    double calibration_ms = 0;  // 0: none recorded
    std::map<std::string, Range> passes;  // "(frame)" or a pass name
};

const json& runs_of(const json& report) {
    if (report.is_array()) return report;
    if (report.is_object() && report.contains("runs") && report["runs"].is_array()) return report["runs"];
    throw std::runtime_error("not a bench report (expected an object with \"runs\" or an array of runs)");
}

Range range(const json& stats) {
    return {stats.value("median", 0.0), stats.value("p5", 0.0), stats.value("p95", 0.0), {}};
}

double calibration_of(const json& j) {
    return j.is_object() && j.contains("calibration") && j["calibration"].is_object()
               ? j["calibration"].value("median_ms", 0.0)
               : 0.0;
}

// "label @ WxH" -> its calibration and ("(frame)" or pass name) -> range and samples
std::map<std::string, RunTimes> index(const json& report) {
    std::map<std::string, RunTimes> out;
    const double header_calibration = calibration_of(report);
    for (const json& run : runs_of(report)) {
        const json& m = run.at("meta");
        std::string label = m.contains("label") ? m["label"].get<std::string>() : m.value("graph", std::string("?"));
        std::string size;
        if (m.contains("size") && m["size"].is_array())  // older reports: [w, h]
            size = std::to_string(m["size"][0].get<int>()) + "x" + std::to_string(m["size"][1].get<int>());
        else if (m.contains("size") && m["size"].is_string())
            size = m["size"].get<std::string>();
        RunTimes& t = out[label + " @ " + size];
        t.calibration_ms = calibration_of(run) > 0 ? calibration_of(run) : header_calibration;
        t.passes["(frame)"] = range(run.at("frame").at("gpu_ms"));
        for (const json& p : run.at("passes")) t.passes[p.at("name").get<std::string>()] = range(p.at("gpu_ms"));
        for (const json& f : run.value("frames", json::array())) {
            if (f.value("warmup", false)) continue;
            if (f.contains("gpu_ms") && f["gpu_ms"].is_number()) t.passes["(frame)"].samples.push_back(f["gpu_ms"].get<double>());
            if (f.contains("passes") && f["passes"].is_object())
                for (auto it = f["passes"].begin(); it != f["passes"].end(); ++it)
                    if (it.value().is_number() && t.passes.count(it.key()))
                        t.passes[it.key()].samples.push_back(it.value().get<double>());
        }
    }
    return out;
}

Range scaled(Range r, double s) {
    r.median *= s, r.p5 *= s, r.p95 *= s;
    for (double& x : r.samples) x *= s;
    return r;
}

double quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const double at = q * double(v.size() - 1);
    const size_t i = size_t(at);
    return i + 1 < v.size() ? v[i] + (v[i + 1] - v[i]) * (at - double(i)) : v.back();
}

// `hi` lies wholly above `lo`: their middle halves (per-frame quartiles) apart where both have
// samples, else their p5..p95 ranges.
bool apart(const Range& lo, const Range& hi) {
    if (!lo.samples.empty() && !hi.samples.empty()) return quantile(hi.samples, 0.25) > quantile(lo.samples, 0.75);
    return hi.p5 > lo.p95;
}

std::string percent_slower(double ratio) {
    char b[96];
    if (ratio >= 1.0) std::snprintf(b, sizeof b, "%.0f %% slower", (ratio - 1.0) * 100.0);
    else std::snprintf(b, sizeof b, "%.0f %% faster", (1.0 / ratio - 1.0) * 100.0);
    return b;
}

}  // namespace

double rank_test_greater(const std::vector<double>& b, const std::vector<double>& a) {
    const size_t n1 = b.size(), n2 = a.size();
    if (n1 == 0 || n2 == 0) return 1.0;
    std::vector<std::pair<double, int>> all;
    for (double x : b) all.push_back({x, 1});
    for (double x : a) all.push_back({x, 2});
    std::sort(all.begin(), all.end(), [](auto& l, auto& r) { return l.first < r.first; });
    double rank_sum_b = 0, ties = 0;
    for (size_t i = 0; i < all.size();) {
        size_t j = i;
        while (j < all.size() && all[j].first == all[i].first) ++j;
        const double mid_rank = 0.5 * double(i + 1 + j);  // ranks i+1 .. j share their mean
        for (size_t k = i; k < j; ++k)
            if (all[k].second == 1) rank_sum_b += mid_rank;
        const double t = double(j - i);
        ties += t * t * t - t;
        i = j;
    }
    const double N = double(n1 + n2), u = rank_sum_b - double(n1) * double(n1 + 1) / 2.0;
    const double mean = double(n1) * double(n2) / 2.0;
    const double var = double(n1) * double(n2) / 12.0 * ((N + 1.0) - ties / (N * (N - 1.0)));
    if (!(var > 0)) return 1.0;
    const double z = (u - mean - 0.5) / std::sqrt(var);  // continuity correction
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

CompareResult compare_reports(const json& baseline, const json& current, double threshold) {
    const auto base = index(baseline), cur = index(current);
    CompareResult r;
    const double bc = calibration_of(baseline), cc = calibration_of(current);
    if (bc > 0 && cc > 0) {
        char line[512];
        std::snprintf(line, sizeof line,
                      "machine: the calibration workload took %.2f ms now and %.2f ms in the baseline: this machine ran "
                      "%s now; now* = now divided by each run's own calibration ratio\n",
                      cc, bc, percent_slower(cc / bc).c_str());
        r.machine = line;
    } else {
        r.machine = std::string("machine: no calibration in ") + (bc > 0 ? "the current results" : "the baseline") +
                    " (a report of an older Pathlet): times compared as measured, so a busy machine reads as slower\n";
    }
    char line[512];
    std::snprintf(line, sizeof line, "%-40s %-22s %9s %9s %9s %8s %7s  %s\n", "run", "pass", "base ms", "now ms",
                  "now* ms", "change*", "p", "verdict");
    r.table += line;
    for (const auto& [run, b_run] : base) {
        auto c = cur.find(run);
        if (c == cur.end()) {
            r.missing.push_back(run);
            continue;
        }
        // base / now calibration: below 1 where the machine was slower now.
        const double factor = b_run.calibration_ms > 0 && c->second.calibration_ms > 0
                                  ? b_run.calibration_ms / c->second.calibration_ms
                                  : 1.0;
        for (const auto& [pass, b] : b_run.passes) {
            auto n = c->second.passes.find(pass);
            if (n == c->second.passes.end()) continue;
            const Range& raw = n->second;
            const Range now = scaled(raw, factor);
            const double change = b.median > 0 ? now.median / b.median - 1.0 : 0.0;
            // The calibration only ever excuses: a slow-down must show both as measured and on
            // the machine's own speed (a calibration that over-corrects cannot make one), and a
            // speed-up likewise.
            const Range slower = scaled(raw, std::min(factor, 1.0)), faster = scaled(raw, std::max(factor, 1.0));
            const char* verdict = "same (within noise)";
            const bool sampled = !raw.samples.empty() && !b.samples.empty();
            double p = sampled ? std::min(rank_test_greater(now.samples, b.samples), rank_test_greater(b.samples, now.samples)) : 0.0;
            if (b.median <= 0 || raw.median <= 0) {
                verdict = "n/a (no time)";
            } else if (const double ps = sampled ? rank_test_greater(slower.samples, b.samples) : 0.0;
                       slower.median > b.median * (1.0 + threshold) && apart(b, slower) && ps < kMaxP &&
                       slower.median - b.median > kMinMs) {
                verdict = "REGRESSION";
                p = ps;
                ++r.regressions;
            } else if (const double pf = sampled ? rank_test_greater(b.samples, faster.samples) : 0.0;
                       faster.median * (1.0 + threshold) < b.median && apart(faster, b) && pf < kMaxP &&
                       b.median - faster.median > kMinMs) {
                verdict = "faster";
                p = pf;
                ++r.improvements;
            }
            ++r.compared;
            char pcol[16];
            if (sampled) std::snprintf(pcol, sizeof pcol, "%.3f", p);
            else std::snprintf(pcol, sizeof pcol, "-");
            std::snprintf(line, sizeof line, "%-40s %-22s %9.3f %9.3f %9.3f %+7.1f%% %7s  %s\n", run.c_str(), pass.c_str(),
                          b.median, raw.median, now.median, change * 100.0, pcol, verdict);
            r.table += line;
        }
    }
    r.table += "  now*: the time on the baseline machine's speed (now x this run's calibration ratio); change* of now*; "
               "p: one-sided rank test of the per-frame samples\n";
    return r;
}

}  // namespace pathlet::cli::bench
