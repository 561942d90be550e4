#include "compare.hpp"

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
};

const json& runs_of(const json& report) {
    if (report.is_array()) return report;
    if (report.is_object() && report.contains("runs") && report["runs"].is_array()) return report["runs"];
    throw std::runtime_error("not a bench report (expected an object with \"runs\" or an array of runs)");
}

Range range(const json& stats) {
    return {stats.value("median", 0.0), stats.value("p5", 0.0), stats.value("p95", 0.0)};
}

// "label @ WxH" -> ("frame" or pass name) -> range
std::map<std::string, std::map<std::string, Range>> index(const json& report) {
    std::map<std::string, std::map<std::string, Range>> out;
    for (const json& run : runs_of(report)) {
        const json& m = run.at("meta");
        std::string label = m.contains("label") ? m["label"].get<std::string>() : m.value("graph", std::string("?"));
        std::string size;
        if (m.contains("size") && m["size"].is_array())  // older reports: [w, h]
            size = std::to_string(m["size"][0].get<int>()) + "x" + std::to_string(m["size"][1].get<int>());
        else if (m.contains("size") && m["size"].is_string())
            size = m["size"].get<std::string>();
        auto& passes = out[label + " @ " + size];
        passes["(frame)"] = range(run.at("frame").at("gpu_ms"));
        for (const json& p : run.at("passes")) passes[p.at("name").get<std::string>()] = range(p.at("gpu_ms"));
    }
    return out;
}

}  // namespace

CompareResult compare_reports(const json& baseline, const json& current, double threshold) {
    const auto base = index(baseline), cur = index(current);
    CompareResult r;
    char line[512];
    std::snprintf(line, sizeof line, "%-40s %-22s %10s %10s %8s  %s\n", "run", "pass", "base ms", "now ms", "change",
                  "verdict");
    r.table += line;
    for (const auto& [run, passes] : base) {
        auto c = cur.find(run);
        if (c == cur.end()) {
            r.missing.push_back(run);
            continue;
        }
        for (const auto& [pass, b] : passes) {
            auto n = c->second.find(pass);
            if (n == c->second.end()) continue;
            const Range& now = n->second;
            const double change = b.median > 0 ? now.median / b.median - 1.0 : 0.0;
            const char* verdict = "same (within noise)";
            if (b.median <= 0 || now.median <= 0) {
                verdict = "n/a (no time)";
            } else if (change > threshold && now.p5 > b.p95 && now.median - b.median > kMinMs) {
                verdict = "REGRESSION";
                ++r.regressions;
            } else if (change < -threshold / (1.0 + threshold) && now.p95 < b.p5 && b.median - now.median > kMinMs) {
                verdict = "faster";
                ++r.improvements;
            }
            ++r.compared;
            std::snprintf(line, sizeof line, "%-40s %-22s %10.3f %10.3f %+7.1f%%  %s\n", run.c_str(), pass.c_str(),
                          b.median, now.median, change * 100.0, verdict);
            r.table += line;
        }
    }
    return r;
}

}  // namespace pathlet::cli::bench
