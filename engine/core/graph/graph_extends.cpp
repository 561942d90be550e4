// Graphs that extend graphs: {"extends": "variant2_oit", ...} reads the base graph (a shipped
// name, a shipped base such as "base/lines" from graphs/base/, or a .json path relative to this
// file) and merges this file's changes into it:
//
//   variables, resources,  by name; an entry's keys replace the base entry's keys, null removes it
//   param_sets
//   passes                 by name: a known name changes that pass ("type" replaces the type,
//                          "params", "inputs", "outputs" merge key by key with null removing a key,
//                          "enabled", "doc" and "param_set" replace, "remove": true drops the pass);
//                          a new name adds a pass and needs a "type"
//   outputs                replace the base's list when given
//   name                   belongs to its file: never inherited (a graph without one is named
//                          after its file, so two graphs never share a name or output folder by accident)
//   description            replaces; plugin_dirs add to the base's (each against its own file)
//
// "extends" may list bases: ["base/core_ao", "variant2_mboit"] merges the second over the first
// (itself with its own bases, as if its content were written in a file extending the first),
// then this file over both. A part several graphs add to different bases (LineAO of the opaque
// core) is written once this way. A later base that shares a base with an earlier one sets that
// shared base's values again.
//
// The merged graph lists its passes in the order they run (data flow; among passes free to run,
// the one a base or the list gives first), the order the compiler finds too.
//
// A param set names parameters several passes take alike, written once:
//   "param_sets": {"lines": {"window": "$window", "lod": "$lod"}}
// A pass with "param_set": "lines" gets them, its own "params" over them (null leaves one out).
// Sets are filled in last, into the whole merged graph, so an extending file that changes a set
// changes every pass that names it.
//
// Each file merged is a layer: the parameters it writes and the hooks it replaces are stamped
// with it, so a parameter written for a hook that a later layer replaced is dropped with its hook
// (graph_hooks.cpp). A hook may be written as one value, "color_hook": {"file": "my_fade.glsl",
// "keep_fast": 0.9}: the file and its own parameters, flattened beside it before merging.
//
// The merged document is then parsed and validated as one graph, so every error names a JSON
// pointer into it (`pathlet graph FILE --expanded` prints it). Bases may extend bases; a cycle,
// an unknown base or param set and a change to a pass the base does not have are errors.
#include "graph_internal.hpp"
#include "plugin_host.hpp"

#include <filesystem>
#include <fstream>
#include <map>
#include <queue>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace pathlet {

using namespace graph_detail;

namespace {

// Shipped bases: parts of graphs in graphs/base/, named "base/NAME" (never rendered or listed as graphs).
std::vector<std::string> shipped_base_names() {
    std::vector<std::string> names;
    std::error_code ec;
    for (fs::directory_iterator it(fs::path(engine_share_dir()) / "graphs" / "base", ec), end; !ec && it != end;
         it.increment(ec))
        if (it->path().extension() == ".json") names.push_back("base/" + it->path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

// A shipped name: folder/name parts without "", "." or "..", never absolute.
bool is_shipped_name(const std::string& ref) {
    if (ref.empty() || ref.front() == '/') return false;
    for (const auto& part : fs::path(ref))
        if (part.empty() || part == "." || part == "..") return false;
    return ref.back() != '/';
}

// The file an "extends" names: a .json path (relative to the extending file's folder) or the
// name of a shipped graph or base (graphs/ in the share folder).
std::string base_path(const std::string& ref, const std::string& from, std::string& err) {
    const fs::path here = fs::path(from).parent_path();
    std::error_code ec;
    if (fs::path(ref).extension() == ".json") {
        const fs::path p = fs::path(ref).is_absolute() ? fs::path(ref) : here / ref;
        if (!fs::is_regular_file(p, ec)) {
            err = "base graph '" + ref + "' not found (looked for " + p.lexically_normal().string() + ")";
            return "";
        }
        return p.lexically_normal().string();
    }
    if (!is_shipped_name(ref)) {
        err = "a base graph is a .json file or the name of a shipped graph, got '" + ref + "'";
        return "";
    }
    const fs::path shipped = fs::path(engine_share_dir()) / "graphs" / (ref + ".json");
    if (fs::is_regular_file(shipped, ec)) return shipped.string();
    const std::vector<std::string> names = shipped_graph_names(), bases = shipped_base_names();
    std::vector<std::string> all = names;
    all.insert(all.end(), bases.begin(), bases.end());
    err = "unknown base graph '" + ref + "'" + did_you_mean(ref, all) + "; shipped graphs: " + join(names) +
          (bases.empty() ? "" : "; shipped bases: " + join(bases)) + " (or give a .json path)";
    return "";
}

// Key-by-key merge of one level: `over`'s keys replace `base`'s, null removes.
void merge_keys(json& base, const json& over) {
    for (const auto& [k, v] : over.items()) {
        if (v.is_null()) base.erase(k);
        else base[k] = v;
    }
}

// Merges an object of named entries (variables, resources, param sets): each entry key by key.
void merge_named(json& base, const json& over) {
    for (const auto& [name, v] : over.items()) {
        if (v.is_null()) base.erase(name);
        else if (base.contains(name) && base[name].is_object() && v.is_object()) merge_keys(base[name], v);
        else base[name] = v;
    }
}

// A pass's params with its param set under them (the set as `sets` has it; none: its own).
json params_with_set(const json& pass, const json& sets) {
    json params = pass.contains("params") && pass["params"].is_object() ? pass["params"] : json::object();
    if (!pass.contains("param_set") || !pass["param_set"].is_string()) return params;
    const std::string set = pass["param_set"].get<std::string>();
    if (!sets.is_object() || !sets.contains(set) || !sets[set].is_object()) return params;
    json out = sets[set];
    merge_keys(out, params);
    return out;
}

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

std::map<std::string, std::map<std::string, std::string>> graph_detail::hook_names(const json& graph) {
    std::map<std::string, std::map<std::string, std::string>> out;
    if (!graph.is_object() || !graph.contains("passes") || !graph["passes"].is_array()) return out;
    const json* vars = graph.contains("variables") && graph["variables"].is_object() ? &graph["variables"] : nullptr;
    for (const json& p : graph["passes"]) {
        if (!p.is_object() || !p.contains("name") || !p["name"].is_string()) continue;
        const json params = params_with_set(p, graph.value("param_sets", json::object()));
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
            change(*it, p, name);
        }
    }

private:
    void change(json& b, const json& p, const std::string& name) {
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
                b[k] = v;  // type, enabled, doc, param_set (and anything else, which the parser names)
            }
        }
    }
    void error(const std::string& ptr, const std::string& msg) { diags_.push_back({file_, ptr, msg}); }
    std::string file_;
    std::vector<Diagnostic>& diags_;
    LayerLog& log_;
};

// `over`, read from `file`, merged into `base` by the rules at the top of this file, as the
// next layer of `log`: the parameters it writes and the hooks it replaces are stamped with it.
void merge_over(json& base, const json& over, const std::string& file, LayerLog& log) {
    std::vector<Diagnostic> diags;
    const auto hooks_before = graph_detail::hook_names(base);
    Merger m(file, diags, log);
    for (const auto& [k, v] : over.items()) {
        if ((k == "variables" || k == "resources" || k == "param_sets") && v.is_object()) {
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
    // The hooks this layer replaced (its own or through a variable's default or a param set).
    for (const auto& [pass, names] : graph_detail::hook_names(base)) {
        const auto was = hooks_before.find(pass);
        if (was == hooks_before.end()) continue;  // a pass this layer adds
        for (const auto& [param, name] : names)
            if (was->second.at(param) != name) log.swaps.push_back({pass, {param, log.layers, file, was->second.at(param), name}});
    }
    ++log.layers;
}

// Fills every pass that names a param set in, and drops the sets: the parser sees plain passes.
void fill_param_sets(json& doc, const std::string& path) {
    if (!doc.is_object()) return;
    const json sets = doc.value("param_sets", json::object());
    doc.erase("param_sets");
    std::vector<Diagnostic> diags;
    std::vector<std::string> names;
    if (!sets.is_object()) diags.push_back({path, "/param_sets", "param_sets must be an object of named parameter sets"});
    else
        for (const auto& [name, set] : sets.items()) {
            names.push_back(name);
            if (!set.is_object())
                diags.push_back({path, "/param_sets/" + pointer_escape(name),
                                 "a param set is an object of parameters (\"window\": \"$window\", ...), got " + set.dump()});
        }
    if (doc.contains("passes") && doc["passes"].is_array() && diags.empty())
        for (size_t i = 0; i < doc["passes"].size(); ++i) {
            json& p = doc["passes"][i];
            if (!p.is_object() || !p.contains("param_set")) continue;
            const json& name = p["param_set"];
            if (!name.is_string() || !sets.contains(name.get<std::string>())) {
                const std::string given = name.is_string() ? name.get<std::string>() : name.dump();
                diags.push_back({path, "/passes/" + std::to_string(i) + "/param_set",
                                 "unknown param set '" + given + "'" + did_you_mean(given, names) +
                                     "; the graph's param sets: " + (names.empty() ? std::string("none") : join(names))});
                continue;
            }
            if (!p.contains("params") || p["params"].is_object()) p["params"] = params_with_set(p, sets);
            p.erase("param_set");  // params of the wrong type: the parser names them
        }
    if (!diags.empty()) throw GraphError(std::move(diags));
}

// The merged passes in the order they run: after the passes whose output they read this frame
// (a resource's writer, or "pass.pin"; "@prev" orders nothing), among passes free to run the one
// listed first, as the compiler orders them. Bases come first in the list, so a base's wall and
// overlay still come out last. A cycle leaves its passes in list order (the validator names it).
void order_passes(json& doc) {
    if (!doc.contains("passes") || !doc["passes"].is_array()) return;
    const json& passes = doc["passes"];
    const int n = int(passes.size());
    std::map<std::string, int> pass_at, writer;
    for (int i = 0; i < n; ++i) {
        if (!passes[i].is_object()) continue;
        pass_at.emplace(passes[i].value("name", ""), i);
        if (passes[i].contains("outputs") && passes[i]["outputs"].is_object())
            for (const auto& [pin, res] : passes[i]["outputs"].items())
                if (res.is_string()) writer.emplace(res.get<std::string>(), i);
    }
    std::vector<std::vector<int>> users(n);
    std::vector<int> pending(n, 0);
    for (int i = 0; i < n; ++i) {
        if (!passes[i].is_object() || !passes[i].contains("inputs") || !passes[i]["inputs"].is_object()) continue;
        std::set<int> deps;
        for (const auto& [pin, ref] : passes[i]["inputs"].items()) {
            if (!ref.is_string() || ref.get<std::string>().find('@') != std::string::npos) continue;
            const std::string r = ref.get<std::string>();
            const auto w = writer.find(r);
            const auto p = pass_at.find(r.substr(0, r.find('.')));
            if (w != writer.end()) deps.insert(w->second);
            else if (r.find('.') != std::string::npos && p != pass_at.end()) deps.insert(p->second);
        }
        deps.erase(i);
        for (int d : deps) users[d].push_back(i), ++pending[i];
    }
    std::priority_queue<int, std::vector<int>, std::greater<int>> ready;
    for (int i = 0; i < n; ++i)
        if (!pending[i]) ready.push(i);
    std::vector<bool> placed(n, false);
    json ordered = json::array();
    while (!ready.empty()) {
        const int p = ready.top();
        ready.pop();
        placed[p] = true;
        ordered.push_back(passes[p]);
        for (int u : users[p])
            if (--pending[u] == 0) ready.push(u);
    }
    for (int i = 0; i < n; ++i)
        if (!placed[i]) ordered.push_back(passes[i]);
    doc["passes"] = std::move(ordered);
}

// Where one expansion puts what it finds (expand_extends's arguments).
struct Expansion {
    std::vector<std::string>& dirs;
    std::vector<std::string>& chain;
    LayerLog& log;
};

void add_once(std::vector<std::string>& list, const std::string& item) {
    if (std::find(list.begin(), list.end(), item) == list.end()) list.push_back(item);
}

// The bases an "extends" names, each with its pointer: one name, or a non-empty list of names.
std::vector<std::pair<std::string, std::string>> base_refs(const json& ext, const std::string& path) {
    const std::string what = "extends must name a base graph (a shipped name or a .json file) or a list of them, got ";
    if (ext.is_string() && !ext.get<std::string>().empty()) return {{ext.get<std::string>(), "/extends"}};
    if (!ext.is_array() || ext.empty()) throw GraphError({{path, "/extends", what + ext.dump()}});
    std::vector<std::pair<std::string, std::string>> refs;
    for (size_t i = 0; i < ext.size(); ++i) {
        const std::string ptr = "/extends/" + std::to_string(i);
        if (!ext[i].is_string() || ext[i].get<std::string>().empty()) throw GraphError({{path, ptr, what + ext[i].dump()}});
        refs.emplace_back(ext[i].get<std::string>(), ptr);
    }
    return refs;
}

json expand_file(json root, const std::string& path, std::vector<std::string> ancestry, Expansion& x);

// The base `ref` names (at `ptr` in `path`), with its own bases merged in; its file in `file`.
json read_base(const std::string& ref, const std::string& ptr, const std::string& path,
               const std::vector<std::string>& ancestry, Expansion& x, std::string& file) {
    std::string err;
    file = base_path(ref, path, err);
    if (!err.empty()) throw GraphError({{path, ptr, err}});
    // A cycle: the base is this file or one that extends it.
    const std::string canonical = fs::weakly_canonical(file).string();
    for (const auto& a : ancestry)
        if (fs::weakly_canonical(a).string() == canonical)
            throw GraphError({{path, ptr, "extends forms a cycle: " + join(ancestry, " -> ") + " -> " + file}});
    if (ancestry.size() >= 16) throw GraphError({{path, ptr, "extends nested deeper than 16 graphs"}});
    add_once(x.chain, file);
    json base = expand_file(read_graph_json(file), file, ancestry, x);
    if (!base.is_object()) throw GraphError({{file, "", "a graph file must be a JSON object"}});
    // The base's plugin folders stay relative to the base's own file.
    if (base.contains("plugin_dirs") && base["plugin_dirs"].is_array())
        for (auto& d : base["plugin_dirs"])
            if (d.is_string() && !fs::path(d.get<std::string>()).is_absolute())
                d = (fs::path(file).parent_path() / d.get<std::string>()).lexically_normal().string();
    base.erase("name");  // a graph's name is its own file's (or that file's name)
    return base;
}

// `root`, read from `path`, with its bases merged in; `ancestry`: the files that extend it, nearest last.
json expand_file(json root, const std::string& path, std::vector<std::string> ancestry, Expansion& x) {
    add_once(x.dirs, fs::path(path).parent_path().lexically_normal().string());
    flatten_hook_values(root, path);
    if (!root.is_object() || !root.contains("extends")) {
        ++x.log.layers;  // a file without bases: what it sets is written at its own layer (unstamped)
        return root;
    }
    const json ext = root["extends"];
    root.erase("extends");
    ancestry.push_back(path);
    const auto refs = base_refs(ext, path);
    std::string file;
    json merged = read_base(refs[0].first, refs[0].second, path, ancestry, x, file);
    for (size_t i = 1; i < refs.size(); ++i) {
        const json later = read_base(refs[i].first, refs[i].second, path, ancestry, x, file);
        merge_over(merged, later, file, x.log);
    }
    merge_over(merged, root, path, x.log);
    return merged;
}

}  // namespace

json graph_detail::expand_extends(json root, const std::string& path, std::vector<std::string>& dirs,
                                  std::vector<std::string>& chain, LayerLog* log) {
    LayerLog ignored;
    Expansion x{dirs, chain, log ? *log : ignored};
    const bool extends = root.is_object() && root.contains("extends");
    json merged = expand_file(std::move(root), path, {}, x);
    fill_param_sets(merged, path);
    if (extends) order_passes(merged);  // a file without bases keeps its own order
    return merged;
}

}  // namespace pathlet
