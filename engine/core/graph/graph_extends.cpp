// Graphs that extend graphs: {"extends": "variant2_oit", ...} reads the base graph (a shipped
// name or a .json path relative to this file) and merges this file's changes into it:
//
//   variables, resources   by name; an entry's keys replace the base entry's keys, null removes it
//   passes                 by name: a known name changes that pass ("type" replaces the type,
//                          "params", "inputs", "outputs" merge key by key with null removing a key,
//                          "enabled" and "doc" replace, "remove": true drops the pass); a new name
//                          adds a pass and needs a "type"
//   outputs                replace the base's list when given
//   name                   belongs to its file: never inherited (a graph without one is named
//                          after its file, so two graphs never share a name or output folder by accident)
//   description            replaces; plugin_dirs add to the base's (each against its own file)
//
// The merged document is then parsed and validated as one graph, so every error names a JSON
// pointer into it (`pathlet graph FILE --expanded` prints it). Bases may extend bases; a cycle,
// an unknown base or a change to a pass the base does not have is an error.
#include "graph_internal.hpp"
#include "plugin_host.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace pathlet {

using namespace graph_detail;

namespace {

// The file an "extends" names: a .json path (relative to the extending file's folder) or the
// name of a shipped graph (graphs/ in the share folder).
std::string base_path(const std::string& ref, const std::string& from, std::string& err) {
    const fs::path here = fs::path(from).parent_path();
    const bool looks_like_path = ref.find('/') != std::string::npos || fs::path(ref).extension() == ".json";
    if (looks_like_path) {
        if (fs::path(ref).extension() != ".json") {
            err = "a base graph is a .json file or the name of a shipped graph, got '" + ref + "'";
            return "";
        }
        const fs::path p = fs::path(ref).is_absolute() ? fs::path(ref) : here / ref;
        std::error_code ec;
        if (!fs::is_regular_file(p, ec)) {
            err = "base graph '" + ref + "' not found (looked for " + p.lexically_normal().string() + ")";
            return "";
        }
        return p.lexically_normal().string();
    }
    const fs::path shipped = fs::path(engine_share_dir()) / "graphs" / (ref + ".json");
    std::error_code ec;
    if (fs::is_regular_file(shipped, ec)) return shipped.string();
    const std::vector<std::string> names = shipped_graph_names();
    err = "unknown base graph '" + ref + "'" + did_you_mean(ref, names) + "; shipped graphs: " + join(names) +
          " (or give a .json path)";
    return "";
}

// Key-by-key merge of one level: `over`'s keys replace `base`'s, null removes.
void merge_keys(json& base, const json& over) {
    for (const auto& [k, v] : over.items()) {
        if (v.is_null()) base.erase(k);
        else base[k] = v;
    }
}

// Merges an object of named entries (variables, resources): each entry key by key.
void merge_named(json& base, const json& over) {
    for (const auto& [name, v] : over.items()) {
        if (v.is_null()) base.erase(name);
        else if (base.contains(name) && base[name].is_object() && v.is_object()) merge_keys(base[name], v);
        else base[name] = v;
    }
}

class Merger {
public:
    Merger(std::string file, std::vector<Diagnostic>& diags, LayerLog& log)
        : file_(std::move(file)), diags_(diags), log_(log) {}

    void passes(json& base, const json& over) {
        if (!base.is_array()) base = json::array();
        for (size_t i = 0; i < over.size(); ++i) {
            const json& p = over[i];
            const std::string ptr = "/passes/" + std::to_string(i);
            if (!p.is_object() || !p.contains("name") || !p["name"].is_string()) {
                error(ptr, "a pass of an extending graph needs a \"name\": the base's pass it changes, or a new one");
                continue;
            }
            const std::string name = p["name"].get<std::string>();
            auto it = std::find_if(base.begin(), base.end(),
                                   [&](const json& b) { return b.is_object() && b.value("name", "") == name; });
            if (it == base.end()) {
                if (!p.contains("type") || p.value("remove", false)) {
                    std::vector<std::string> names;
                    for (const auto& b : base) names.push_back(b.value("name", ""));
                    error(ptr + "/name", "no pass '" + name + "' in the base graph to " +
                                             (p.value("remove", false) ? "remove" : "change") + did_you_mean(name, names) +
                                             "; its passes: " + join(names) + " (a new pass needs a \"type\")");
                    continue;
                }
                json added = p;
                added.erase("remove");
                if (added.contains("params") && added["params"].is_object())
                    for (const auto& [key, value] : added["params"].items()) log_.written[name][key] = log_.layers;
                base.push_back(std::move(added));
                continue;
            }
            if (p.contains("remove")) {
                if (!p["remove"].is_boolean()) error(ptr + "/remove", "remove must be true or false");
                else if (p["remove"].get<bool>()) {
                    base.erase(it);
                    continue;
                }
            }
            json& b = *it;
            for (const auto& [k, v] : p.items()) {
                if (k == "name" || k == "remove") continue;
                if ((k == "params" || k == "inputs" || k == "outputs") && v.is_object()) {
                    if (!b.contains(k) || !b[k].is_object()) b[k] = json::object();
                    if (k == "params")
                        for (const auto& [key, value] : v.items()) log_.written[name][key] = log_.layers;
                    merge_keys(b[k], v);
                } else if (v.is_null()) {
                    b.erase(k);
                } else {
                    b[k] = v;  // type, enabled, doc (and anything else, which the parser names)
                }
            }
        }
    }

private:
    void error(const std::string& ptr, const std::string& msg) { diags_.push_back({file_, ptr, msg}); }
    std::string file_;
    std::vector<Diagnostic>& diags_;
    LayerLog& log_;
};

}  // namespace

std::map<std::string, std::map<std::string, std::string>> graph_detail::hook_names(const json& graph) {
    std::map<std::string, std::map<std::string, std::string>> out;
    if (!graph.is_object() || !graph.contains("passes") || !graph["passes"].is_array()) return out;
    const json* vars = graph.contains("variables") && graph["variables"].is_object() ? &graph["variables"] : nullptr;
    for (const json& p : graph["passes"]) {
        if (!p.is_object() || !p.contains("name") || !p["name"].is_string()) continue;
        const json params = p.value("params", json::object());
        for (const HookRole role : kHookRoles) {
            const char* param = hook_role(role).param;
            std::string name;
            if (params.is_object() && params.contains(param) && params[param].is_string()) {
                name = params[param].get<std::string>();
                if (is_variable_ref(params[param]) && vars && vars->contains(name.substr(1))) {
                    const json& v = (*vars)[name.substr(1)];
                    if (v.is_object() && v.contains("default") && v["default"].is_string()) name = v["default"].get<std::string>();
                }
            }
            out[p["name"].get<std::string>()][param] = name;
        }
    }
    return out;
}

namespace {

// A hook as one value: "color_hook": {"file": "my_fade.glsl", "keep_fast": 0.9} is the file and
// its own parameters, written beside it in the pass's params (as the flat form writes them).
void flatten_hook_values(json& root, const std::string& path) {
    if (!root.is_object() || !root.contains("passes") || !root["passes"].is_array()) return;
    std::vector<Diagnostic> diags;
    for (size_t i = 0; i < root["passes"].size(); ++i) {
        json& p = root["passes"][i];
        if (!p.is_object() || !p.contains("params") || !p["params"].is_object()) continue;
        json& params = p["params"];
        for (const HookRole role : kHookRoles) {
            const char* key = hook_role(role).param;
            if (!params.contains(key) || !params[key].is_object()) continue;
            const std::string ptr = "/passes/" + std::to_string(i) + "/params/" + key;
            const json value = params[key];
            if (!value.contains("file") || !value["file"].is_string()) {
                diags.push_back({path, ptr, std::string("a hook given as an object names its file: {\"file\": \"my_fade.glsl\", ...its parameters}")});
                continue;
            }
            params[key] = value["file"];
            for (const auto& [k, v] : value.items()) {
                if (k == "file") continue;
                if (params.contains(k))
                    diags.push_back({path, ptr + "/" + pointer_escape(k), "parameter '" + k + "' is given twice: in " + key + " and beside it"});
                params[k] = v;
            }
        }
    }
    if (!diags.empty()) throw GraphError(std::move(diags));
}

}  // namespace

json graph_detail::expand_extends(json root, const std::string& path, std::vector<std::string>& dirs,
                                  std::vector<std::string>& chain, LayerLog* log) {
    LayerLog ignored;
    if (!log) log = &ignored;
    flatten_hook_values(root, path);
    dirs.push_back(fs::path(path).parent_path().lexically_normal().string());
    if (!root.is_object() || !root.contains("extends")) {
        ++log->layers;  // the deepest base: layer 0, what every parameter it sets was written at
        return root;
    }
    const json ext = root["extends"];
    root.erase("extends");
    if (!ext.is_string() || ext.get<std::string>().empty())
        throw GraphError({{path, "/extends", "extends must name a base graph (a shipped name or a .json file), got " +
                                                 ext.dump()}});
    std::string err;
    const std::string base_file = base_path(ext.get<std::string>(), path, err);
    if (!err.empty()) throw GraphError({{path, "/extends", err}});
    // A cycle: the base is this file or one it already extends.
    std::vector<std::string> seen{fs::weakly_canonical(path).string()};
    for (const auto& c : chain) seen.push_back(fs::weakly_canonical(c).string());
    if (std::find(seen.begin(), seen.end(), fs::weakly_canonical(base_file).string()) != seen.end()) {
        std::string cycle = path;
        for (const auto& c : chain) cycle += " -> " + c;
        throw GraphError({{path, "/extends", "extends forms a cycle: " + cycle + " -> " + base_file}});
    }
    if (chain.size() >= 16) throw GraphError({{path, "/extends", "extends nested deeper than 16 graphs"}});
    chain.push_back(base_file);
    json base = read_graph_json(base_file);
    base = expand_extends(std::move(base), base_file, dirs, chain, log);
    if (!base.is_object()) throw GraphError({{base_file, "", "a graph file must be a JSON object"}});

    // The base's plugin folders stay relative to the base's own file.
    if (base.contains("plugin_dirs") && base["plugin_dirs"].is_array())
        for (auto& d : base["plugin_dirs"])
            if (d.is_string() && !fs::path(d.get<std::string>()).is_absolute())
                d = (fs::path(base_file).parent_path() / d.get<std::string>()).lexically_normal().string();

    base.erase("name");  // a graph's name is its own file's (or that file's name)

    std::vector<Diagnostic> diags;
    const auto hooks_before = hook_names(base);
    Merger m(path, diags, *log);
    for (const auto& [k, v] : root.items()) {
        if ((k == "variables" || k == "resources") && v.is_object()) {
            if (!base.contains(k) || !base[k].is_object()) base[k] = json::object();
            merge_named(base[k], v);
        } else if (k == "passes" && v.is_array()) {
            m.passes(base[k], v);
        } else if (k == "plugin_dirs" && v.is_array() && base.contains(k) && base[k].is_array()) {
            for (const auto& d : v) base[k].push_back(d);
        } else {
            base[k] = v;  // name, description, version, outputs; wrong types are the parser's to name
        }
    }
    if (!diags.empty()) throw GraphError(std::move(diags));
    // The hooks this file replaced (its own or through a variable's default).
    const auto hooks_after = hook_names(base);
    for (const auto& [pass, names] : hooks_after) {
        const auto was = hooks_before.find(pass);
        if (was == hooks_before.end()) continue;  // a pass this file adds
        for (const auto& [param, name] : names)
            if (was->second.at(param) != name)
                log->swaps.push_back({pass, {param, log->layers, path, was->second.at(param), name}});
    }
    ++log->layers;
    return base;
}

}  // namespace pathlet
