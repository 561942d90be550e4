// Parses and validates experiment files with the same kind of errors graph files get:
// the file, a JSON pointer to the bad value and a did-you-mean for misspelt keys.
#include "experiment.hpp"

#include "renderer.hpp"
#include "util/text.hpp"
#include <pathlet/text.hpp>

#include <pathlet/scene.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace pathlet::cli::bench {
namespace {

using nlohmann::json;
using text::did_you_mean;
using text::pointer_escape;

struct Ctx {
    std::string origin;
    [[noreturn]] void fail(const std::string& ptr, const std::string& msg) const {
        throw DataError(origin + ": " + (ptr.empty() ? "/" : ptr) + ": " + msg);
    }
    void keys(const json& j, const std::string& ptr, const std::vector<std::string>& allowed) const {
        if (!j.is_object()) fail(ptr, "expected an object");
        for (auto it = j.begin(); it != j.end(); ++it) {
            bool ok = false;
            for (const auto& k : allowed) ok |= k == it.key();
            if (!ok)
                fail(ptr + "/" + pointer_escape(it.key()),
                     "unknown key '" + it.key() + "'" + did_you_mean(it.key(), allowed));
        }
    }
    std::string str(const json& j, const std::string& ptr) const {
        if (!j.is_string()) fail(ptr, "expected a string");
        return j.get<std::string>();
    }
    // Strings, or numbers written as they would be on the command line.
    std::string scalar(const json& j, const std::string& ptr) const {
        if (j.is_string()) return j.get<std::string>();
        if (j.is_number_integer()) return std::to_string(j.get<long long>());
        if (j.is_number()) {
            std::ostringstream s;
            s << j.get<double>();
            return s.str();
        }
        if (j.is_boolean()) return j.get<bool>() ? "true" : "false";
        fail(ptr, "expected a string, number or boolean");
    }
    std::vector<std::string> sets(const json& j, const std::string& ptr) const {
        if (!j.is_array()) fail(ptr, "expected an array of \"NAME=VALUE\" strings");
        std::vector<std::string> out;
        for (size_t i = 0; i < j.size(); ++i) {
            std::string s = str(j[i], ptr + "/" + std::to_string(i));
            if (s.find('=') == std::string::npos || s.front() == '=')
                fail(ptr + "/" + std::to_string(i), "expected NAME=VALUE, got '" + s + "'");
            out.push_back(s);
        }
        return out;
    }
    int count(const json& j, const std::string& ptr, int min, int max) const {
        if (!j.is_number_integer() || j.get<long long>() < min || j.get<long long>() > max)
            fail(ptr, "expected an integer >= " + std::to_string(min) + " and <= " + std::to_string(max));
        return int(j.get<long long>());
    }
};

// "graphs": names or {"graph", "label", "set"}; a graph file found beside the experiment file.
std::vector<ExperimentGraph> parse_graphs(const Ctx& c, const json& gs, const std::string& origin) {
    std::vector<ExperimentGraph> graphs;
    if (!gs.is_array() || gs.empty()) c.fail("/graphs", "expected a non-empty array");
    for (size_t i = 0; i < gs.size(); ++i) {
        const std::string p = "/graphs/" + std::to_string(i);
        ExperimentGraph g;
        if (gs[i].is_string()) {
            g.graph = gs[i].get<std::string>();
        } else {
            c.keys(gs[i], p, {"graph", "label", "set"});
            if (!gs[i].contains("graph")) c.fail(p, "missing 'graph' (a graph file or shipped name)");
            g.graph = c.str(gs[i]["graph"], p + "/graph");
            // A graph file is found beside the experiment file (a shipped name stays a name).
            const std::filesystem::path gp(g.graph), here = std::filesystem::path(origin).parent_path();
            if (gp.extension() == ".json" && gp.is_relative() && !here.empty()) g.graph = (here / gp).string();
            if (gs[i].contains("label")) g.label = c.str(gs[i]["label"], p + "/label");
            if (gs[i].contains("set")) g.sets = c.sets(gs[i]["set"], p + "/set");
        }
        if (g.graph.empty()) c.fail(p, "empty graph name");
        if (g.label.empty()) g.label = g.graph;
        for (const auto& other : graphs)
            if (other.label == g.label) c.fail(p, "label '" + g.label + "' is used twice; give one a \"label\"");
        graphs.push_back(g);
    }
    return graphs;
}

// "data": data sets, each a phantom preset or a file (with an optional mesh) beside the experiment file.
std::vector<DataSet> parse_data(const Ctx& c, const json& d, const std::string& origin) {
    std::vector<DataSet> data;
    if (!d.is_array() || d.empty()) c.fail("/data", "expected a non-empty array of {\"phantom\": ...} or {\"file\": ...}");
    const std::filesystem::path base = std::filesystem::path(origin).parent_path();
    for (size_t i = 0; i < d.size(); ++i) {
        const std::string p = "/data/" + std::to_string(i);
        c.keys(d[i], p, {"label", "phantom", "file", "mesh"});
        DataSet ds;
        if (d[i].contains("label")) ds.label = c.str(d[i]["label"], p + "/label");
        if (d[i].contains("phantom")) ds.phantom = c.str(d[i]["phantom"], p + "/phantom");
        auto rel = [&](const std::string& f) {
            std::filesystem::path fp(f);
            return fp.is_relative() && !base.empty() ? (base / fp).string() : f;
        };
        if (d[i].contains("file")) ds.file = rel(c.str(d[i]["file"], p + "/file"));
        if (d[i].contains("mesh")) ds.mesh = rel(c.str(d[i]["mesh"], p + "/mesh"));
        if (ds.phantom.empty() == ds.file.empty()) c.fail(p, "give exactly one of 'phantom' (study, small) and 'file'");
        if (!ds.phantom.empty() && ds.phantom != "study" && ds.phantom != "small")
            c.fail(p + "/phantom", "unknown preset '" + ds.phantom + "'" + did_you_mean(ds.phantom, {"study", "small"}) +
                                       "; presets: study, small");
        if (!ds.file.empty() && !std::filesystem::exists(ds.file)) c.fail(p + "/file", "no such file: " + ds.file);
        if (!ds.mesh.empty() && !std::filesystem::exists(ds.mesh)) c.fail(p + "/mesh", "no such file: " + ds.mesh);
        if (ds.label.empty())
            ds.label = ds.phantom.empty() ? std::filesystem::path(ds.file).stem().string() : ds.phantom;
        data.push_back(ds);
    }
    return data;
}

}  // namespace

Experiment parse_experiment(const json& j, const std::string& origin) {
    Ctx c{origin};
    c.keys(j, "", {"$schema", "name", "description", "graphs", "sizes", "time", "frames", "warmup", "set", "camera",
                   "orbit_deg_per_s", "sweep", "data"});
    Experiment e;
    if (j.contains("name")) e.name = c.str(j["name"], "/name");
    if (e.name.empty()) e.name = std::filesystem::path(origin).stem().string();
    if (j.contains("description")) e.description = c.str(j["description"], "/description");
    if (!j.contains("graphs")) c.fail("", "missing 'graphs' (a list of graph files or shipped names)");
    e.graphs = parse_graphs(c, j["graphs"], origin);
    if (j.contains("sizes")) {
        const json& s = j["sizes"];
        if (!s.is_array() || s.empty()) c.fail("/sizes", "expected a non-empty array of \"WxH\" strings");
        e.sizes.clear();
        for (size_t i = 0; i < s.size(); ++i) {
            std::string v = c.str(s[i], "/sizes/" + std::to_string(i));
            try {
                parse_size(v);  // the rule of --size
            } catch (const std::invalid_argument&) {
                c.fail("/sizes/" + std::to_string(i), "expected WxH such as 1280x720 (1..16384), got '" + v + "'");
            }
            e.sizes.push_back(v);
        }
    }
    if (j.contains("time")) {
        e.time = c.scalar(j["time"], "/time");
        try {
            parse_time_range(e.time);  // the rule of --time
        } catch (const std::invalid_argument& ex) {
            std::string why = ex.what();
            why.erase(0, why.find(": ") + 2);  // without the option's name: it came from this file
            c.fail("/time", "'" + e.time + "': " + why);
        }
    }
    // Caps as for a graph's numbers: a typo of 1e9 frames is refused, not run for a week.
    if (j.contains("frames")) e.frames = c.count(j["frames"], "/frames", 1, 100000);
    if (j.contains("warmup")) e.warmup = c.count(j["warmup"], "/warmup", 0, 100000);
    if (j.contains("set")) e.sets = c.sets(j["set"], "/set");
    if (j.contains("camera")) {
        e.camera = c.str(j["camera"], "/camera");
        std::filesystem::path p(e.camera), base = std::filesystem::path(origin).parent_path();
        if (!e.camera.empty() && p.is_relative() && !base.empty()) e.camera = (base / p).string();
    }
    if (j.contains("orbit_deg_per_s")) {
        if (!j["orbit_deg_per_s"].is_number()) c.fail("/orbit_deg_per_s", "expected a number");
        e.orbit_deg_per_s = j["orbit_deg_per_s"].get<double>();
    }
    if (j.contains("sweep")) {
        const json& s = j["sweep"];
        c.keys(s, "/sweep", {"param", "values"});
        if (!s.contains("param")) c.fail("/sweep", "missing 'param' (a --set name such as lineao.samples)");
        e.sweep.param = c.str(s["param"], "/sweep/param");
        if (e.sweep.param.empty() || e.sweep.param.find('=') != std::string::npos)
            c.fail("/sweep/param", "expected a parameter name without '='");
        if (!s.contains("values") || !s["values"].is_array() || s["values"].empty())
            c.fail("/sweep/values", "expected a non-empty array of values");
        for (size_t i = 0; i < s["values"].size(); ++i)
            e.sweep.values.push_back(c.scalar(s["values"][i], "/sweep/values/" + std::to_string(i)));
    }
    if (j.contains("data")) e.data = parse_data(c, j["data"], origin);
    return e;
}

Experiment load_experiment(const std::string& path) {
    return parse_experiment(text::read_json_file(path, "experiment file"), path);
}

std::vector<Run> plan_runs(const Experiment& e) {
    std::vector<Run> runs;
    std::vector<std::string> values = e.sweep.values;
    if (values.empty()) values.push_back("");
    const size_t nd = std::max<size_t>(1, e.data.size());
    for (size_t d = 0; d < nd; ++d)
        for (size_t g = 0; g < e.graphs.size(); ++g)
            for (const auto& v : values)
                for (const auto& s : e.sizes) {
                    Run r{d, g, v, s, ""};
                    r.label = e.graphs[g].label + (v.empty() ? "" : " " + e.sweep.param + "=" + v) +
                                   (e.data.size() > 1 ? " on " + e.data[d].label : "");
                    runs.push_back(r);
                }
    return runs;
}

}  // namespace pathlet::cli::bench
