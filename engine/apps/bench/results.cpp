#include "bench/results.hpp"

#include "bench/calibration.hpp"
#include "common/point_memory.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

namespace pathlet::cli::bench {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A run's entry: profiler summary (meta, timing, frame, passes) plus "frames" (every frame).
json run_entry(const Profiler& p, const json& meta) {
    json e = p.to_json(meta);
    json frames = json::array();
    const auto& names = p.pass_names();
    for (const auto& f : p.frames()) {
        json passes = json::object();
        for (const auto& s : f.passes)
            if (s.gpu.valid) passes[names[size_t(s.pass)]] = s.gpu.duration();
        frames.push_back({{"frame", f.index},
                          {"warmup", f.warmup},
                          {"gpu_ms", f.gpu.valid ? json(f.gpu.duration()) : json()},
                          {"cpu_ms", f.cpu.valid ? json(f.cpu.duration()) : json()},
                          {"passes", passes}});
    }
    e["frames"] = frames;
    return e;
}

// Machine description for the header: host, CPU model, cores.
json machine_info() {
    char host[256] = {0};
    gethostname(host, sizeof host - 1);
    std::string cpu;
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0) {
            cpu = line.substr(line.find(':') + 2);
            break;
        }
    return {{"host", host}, {"cpu", cpu}, {"cores", std::thread::hardware_concurrency()}};
}

std::string file_hash(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "";
    uint64_t h = 1469598103934665603ull;
    char c;
    while (in.get(c)) {
        h ^= uint8_t(c);
        h *= 1099511628211ull;
    }
    char b[17];
    std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
    return b;
}

}  // namespace

Results::Results(const Experiment& e, const std::string& command, const std::string& gl_renderer, const json& graphs,
                 size_t planned_runs, const Shard& shard)
    : j_({{"experiment", e.name},
          {"description", e.description},
          {"command", command},
          {"machine", machine_info()},
          {"gl_renderer", gl_renderer},
          {"graphs", graphs},
          {"sizes", e.sizes},
          {"time", e.time},
          {"frames", e.frames},
          {"warmup", e.warmup},
          {"sweep_param", e.sweep.param},
          {"planned_runs", planned_runs},
          {"complete", false},
          {"runs", json::array()}}) {
    if (shard.active()) j_["shard"] = {{"index", shard.index}, {"count", shard.count}};
}

void Results::add_data(const Scene& scene, const TimeRange& time) {
    char t[96];
    if (time.times().size() == 1) std::snprintf(t, sizeof t, "%g", time.start);
    else std::snprintf(t, sizeof t, "%g:%g:%g", time.start, time.end, time.step);
    // The GPU memory of the line points, as GpuScene::upload allocates it for this data.
    const GpuScene::PointLayout layout = GpuScene::default_point_layout();
    const GpuScene::PointMemory m = point_memory_of(scene.lines, layout);
    const json gpu = {{"layout", GpuScene::layout_name(layout)}, {"bytes", m.total()},         {"bytes_per_point", m.per_point()},
                      {"positions", m.positions},                {"attributes", m.attributes}, {"lod", m.lod},
                      {"chunks", m.chunk_boxes},                 {"summary", point_memory_text(m, layout)}};
    j_["data"].push_back({{"source", scene.source},
                          {"lines", scene.lines.line_count()},
                          {"points", scene.lines.point_count()},
                          {"mesh_triangles", scene.mesh ? scene.mesh->index.size() / 3 : 0},
                          {"time", t},
                          {"gpu_points", gpu}});
}

void Results::add_run(size_t index, const Run& run, const ExperimentGraph& g, const std::string& graph_path,
                      const std::vector<std::string>& sets, const std::string& data, const Profiler& p,
                      const std::string& image) {
    json meta = {{"index", index},       {"label", run.label},          {"graph_label", g.label},
                 {"graph", g.graph},     {"graph_path", graph_path},    {"size", run.size},
                 {"sweep_value", run.sweep_value}, {"sets", sets},      {"data", data},
                 {"renderer", j_["gl_renderer"]}};
    if (!image.empty()) meta["image"] = image;
    j_["timing_backend"] = p.backend_description();
    j_["runs"].push_back(run_entry(p, meta));
}

void Results::add_calibration(const std::string& workload, const std::vector<double>& before_ms,
                              const std::vector<double>& after_ms) {
    if (j_["runs"].empty()) return;
    std::vector<double> both = before_ms;
    both.insert(both.end(), after_ms.begin(), after_ms.end());
    j_["runs"].back()["calibration"] = {{"before_ms", before_ms}, {"after_ms", after_ms}, {"median_ms", median_of(both)}};
    std::vector<double> all;
    for (const json& r : j_["runs"])
        if (r.contains("calibration"))
            for (const char* k : {"before_ms", "after_ms"})
                for (const json& v : r["calibration"][k]) all.push_back(v.get<double>());
    j_["calibration"] = {{"workload", workload}, {"median_ms", median_of(all)}};
}

json graph_entry(const std::string& graph, const std::string& path) {
    return {{"graph", graph}, {"path", path}, {"fnv1a64", file_hash(path)}};
}

json merge_results(const std::vector<std::pair<std::string, json>>& parts, const std::string& out_dir) {
    json merged;
    std::map<size_t, json> runs;
    for (const auto& [dir, part] : parts) {
        if (merged.is_null()) merged = part;
        else if (part.value("experiment", "") != merged.value("experiment", "") ||
                 part.value("planned_runs", 0) != merged.value("planned_runs", 0))
            throw std::runtime_error(dir + "/results.json: from another experiment than " + parts.front().first);
        for (const json& r : part.at("runs")) {
            size_t k = r.at("meta").at("index").get<size_t>();
            if (runs.count(k)) throw std::runtime_error(dir + ": run " + std::to_string(k) + " is in two shards");
            if (r["meta"].contains("image") && r["meta"]["image"].is_string()) {
                const std::string rel = r["meta"]["image"];
                fs::create_directories((fs::path(out_dir) / rel).parent_path());
                fs::copy_file(fs::path(dir) / rel, fs::path(out_dir) / rel, fs::copy_options::overwrite_existing);
            }
            runs[k] = r;
        }
    }
    merged.erase("shard");
    merged["runs"] = json::array();
    for (auto& [k, r] : runs) merged["runs"].push_back(r);
    merged["complete"] = runs.size() == merged.value("planned_runs", size_t(0));
    std::vector<double> all;  // the machine's speed over every shard's runs
    for (const json& r : merged["runs"])
        if (r.contains("calibration"))
            for (const char* k : {"before_ms", "after_ms"})
                for (const json& v : r["calibration"][k]) all.push_back(v.get<double>());
    if (!all.empty()) merged["calibration"]["median_ms"] = median_of(all);
    return merged;
}

}  // namespace pathlet::cli::bench
