#include "report.hpp"

#include "svg_plot.hpp"
#include "util/atomic_file.hpp"
#include "util/text.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>

namespace pathlet::cli::bench {
namespace {

using nlohmann::json;
using text::csv_field;

std::string fmt(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4f", v);
    return b;
}

std::string meta_cols(const json& m) {
    return csv_field(m.value("label", "")) + "," + csv_field(m.value("graph", "")) + "," + m.value("size", "") + "," +
           csv_field(m.value("sweep_value", ""));
}

}  // namespace

std::string summary_csv(const json& report) {
    std::string out = "label,graph,size,sweep_value,pass,depth,n,median_ms,p5_ms,p95_ms,share_pct\n";
    for (const json& r : report.at("runs")) {
        const std::string m = meta_cols(r.at("meta"));
        for (const json& p : r.at("passes")) {
            const json& g = p.at("gpu_ms");
            out += m + "," + csv_field(p.value("name", "")) + "," + std::to_string(p.value("depth", 0)) + "," +
                   std::to_string(g.value("n", 0)) + "," + fmt(g.value("median", 0.0)) + "," + fmt(g.value("p5", 0.0)) +
                   "," + fmt(g.value("p95", 0.0)) + "," + fmt(p.value("share_pct", 0.0)) + "\n";
        }
        const json& f = r.at("frame").at("gpu_ms");
        out += m + ",(frame),0," + std::to_string(f.value("n", 0)) + "," + fmt(f.value("median", 0.0)) + "," +
               fmt(f.value("p5", 0.0)) + "," + fmt(f.value("p95", 0.0)) + ",100.0000\n";
    }
    return out;
}

std::string frames_csv(const json& report) {
    std::string out = "label,graph,size,sweep_value,frame,warmup,pass,gpu_ms\n";
    for (const json& r : report.at("runs")) {
        const std::string m = meta_cols(r.at("meta"));
        for (const json& f : r.value("frames", json::array())) {
            const std::string pre = m + "," + std::to_string(f.value("frame", 0)) + "," +
                                    (f.value("warmup", false) ? "1" : "0") + ",";
            if (f.contains("gpu_ms") && f["gpu_ms"].is_number()) out += pre + "(frame)," + fmt(f["gpu_ms"].get<double>()) + "\n";
            for (auto it = f["passes"].begin(); it != f["passes"].end(); ++it)
                out += pre + csv_field(it.key()) + "," + fmt(it.value().get<double>()) + "\n";
        }
    }
    return out;
}

std::string summary_table(const std::vector<SummaryRow>& rows) {
    std::string out;
    char line[512];
    std::snprintf(line, sizeof line, "  %-40s %10s %10s %10s %9s %9s  %s\n", "run", "median ms", "p5 ms", "p95 ms",
                  "frame fps", "wall fps", "chunks drawn p1+p2 / occluded / frustum-culled");
    out += line;
    bool any_unstable = false;
    for (const SummaryRow& r : rows) {
        const bool unstable = r.gpu_timing && Profiler::unstable(r.frame);
        any_unstable |= unstable;
        std::snprintf(line, sizeof line, "  %-40s %10.2f %10.2f %10.2f %9.1f %9.1f  %s%s\n", r.label.c_str(), r.frame.median,
                      r.frame.p5, r.frame.p95, r.frame.median > 0 ? 1000.0 / r.frame.median : 0.0, r.wall_fps,
                      r.chunks.c_str(), unstable ? "  UNSTABLE" : "");
        out += line;
    }
    out += "  frame fps: 1000 / the median frame time; wall fps: frames over the wall clock of the run (with "
           "waiting and read-back)\n";
    if (any_unstable) {
        std::snprintf(line, sizeof line,
                      "  UNSTABLE: frame times spread more than p95/p5 = %.1f (a GPU clock that changed during the "
                      "run, or other load); quote the p5..p95 range\n",
                      Profiler::kUnstableRatio);
        out += line;
    }
    return out;
}

std::vector<std::string> write_report_dir(const std::string& dir, const json& report) {
    std::vector<std::string> files = {"results.json", "summary.csv", "frames.csv", "passes.svg"};
    write_file_atomic(dir + "/results.json", report.dump(1));
    write_file_atomic(dir + "/summary.csv", summary_csv(report));
    write_file_atomic(dir + "/frames.csv", frames_csv(report));

    // Bars: top-level passes only (nested ones are inside their parent's time), grouped by size
    // in the experiment's order, plan order within a size.
    std::vector<std::string> sizes = report.value("sizes", std::vector<std::string>{});
    std::vector<Bar> bars;
    for (const json& r : report.at("runs")) {
        const std::string size = r["meta"].value("size", "");
        if (std::find(sizes.begin(), sizes.end(), size) == sizes.end()) sizes.push_back(size);
        Bar b{r["meta"].value("label", "") + " " + size, size, {}};
        for (const json& p : r.at("passes"))
            if (p.value("depth", 0) == 0) b.parts.push_back({p.value("name", ""), p["gpu_ms"].value("median", 0.0)});
        const json& f = r.at("frame").at("gpu_ms");
        b.frame_median = f.value("median", 0.0);
        b.frame_p5 = f.value("p5", 0.0);
        b.frame_p95 = f.value("p95", 0.0);
        bars.push_back(b);
    }
    std::stable_sort(bars.begin(), bars.end(), [&](const Bar& a, const Bar& b) {
        return std::find(sizes.begin(), sizes.end(), a.group) < std::find(sizes.begin(), sizes.end(), b.group);
    });
    const std::string title = report.value("experiment", std::string("bench")) + ": median time per pass (" +
                              report.value("gl_renderer", std::string("?")) + ")";
    write_file_atomic(dir + "/passes.svg", stacked_bars_svg(title, bars));

    const std::string param = report.value("sweep_param", std::string());
    if (!param.empty()) {
        std::map<std::string, Series> by;  // graph label @ size
        std::vector<std::string> order;
        size_t k = 0;
        for (const json& r : report.at("runs")) {
            const json& m = r.at("meta");
            std::string key = m.value("graph_label", "") + " " + m.value("size", "");
            if (!by.count(key)) order.push_back(key);
            Series& s = by[key];
            s.label = key;
            const std::string v = m.value("sweep_value", "");
            char* end = nullptr;
            double x = std::strtod(v.c_str(), &end);
            s.x.push_back(end && *end == 0 && !v.empty() ? x : double(k));
            const json& f = r.at("frame").at("gpu_ms");
            s.median.push_back(f.value("median", 0.0));
            s.p5.push_back(f.value("p5", 0.0));
            s.p95.push_back(f.value("p95", 0.0));
            ++k;
        }
        std::vector<Series> series;
        for (const auto& key : order) series.push_back(by[key]);
        write_file_atomic(dir + "/sweep.svg",
                          line_chart_svg(report.value("experiment", std::string("bench")) + ": frame time against " + param,
                                         param, series));
        files.push_back("sweep.svg");
    }
    return files;
}

}  // namespace pathlet::cli::bench
