// Swapping a hook swaps its parameters. A base graph sets the parameters of the hook it uses
// (variant2_oit's fill_list sets tail_fade and head_fade, the end fade's); a graph that extends
// it, a --set or Python's Graph.set that puts another hook there would otherwise carry them
// over to a hook that has none of them. Here they are dropped, with a note naming them, and so
// are the graph variables that fed only them. A parameter the replacing graph sets itself is
// kept, so one the new hook lacks still gets "unknown parameter ... did you mean".
#include "graph_internal.hpp"
#include "hook_params.hpp"

#include <algorithm>
#include <filesystem>

namespace pathlet {

using namespace graph_detail;

namespace {

// The hook file a hook parameter names in `params` (written value or "$variable"), else its default.
std::string hook_file(const GraphFile& g, const ParamDecl& d, const json& params) {
    if (!params.contains(d.name)) return d.def.get<std::string>();
    json v;
    if (!resolve_param(g, d, params[d.name], v).empty() || !v.is_string()) return "";
    return v.get<std::string>();
}

bool references(const json& value, const std::string& variable) {
    return is_variable_ref(value) && value.get<std::string>().substr(1) == variable;
}

bool variable_used(const GraphFile& g, const std::string& name) {
    for (const auto& p : g.passes) {
        if (references(p.enabled, name)) return true;
        for (const auto& [k, v] : p.params.items())
            if (references(v, name)) return true;
    }
    return false;
}

std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

}  // namespace

namespace graph_detail {

void swap_hook_params(GraphFile& g, PassDecl& p, const PassTypeInfo& t, const PassDecl::ParamsChange& change) {
    std::vector<std::string> swaps;       // "color_hook my_fade.glsl replaces fade_opacity.frag"
    std::set<std::string> replaced;       // parameters the replaced hooks declare
    std::vector<std::string> dirs;
    for (const ParamDecl& d : t.params) {
        if (d.hook.empty() || std::find(change.keys.begin(), change.keys.end(), d.name) == change.keys.end()) continue;
        const std::string before = hook_file(g, d, change.before), now = hook_file(g, d, p.params);
        if (before == now) continue;
        swaps.push_back(d.name + " " + (now.empty() ? std::string("(the kit's default)") : quoted(file_name(now))) +
                        " replaces " + (before.empty() ? std::string("the kit's default") : quoted(file_name(before))));
        if (before.empty() || !check_hook_name(before, g.dirs).empty()) continue;
        if (dirs.empty()) dirs = hook_search_path(t, g.dirs);
        try {
            for (const ParamDecl& h : hook_params(before, d.hook, dirs)) replaced.insert(h.name);
        } catch (const HookError&) {
            // The replaced hook cannot be read: nothing is known to be its; validation names the rest.
        }
    }
    if (replaced.empty()) return;
    std::string err, at;
    const auto now = pass_instance_type(g, p, t, err, at);
    if (!err.empty()) return;  // the new hook is wrong: validation says so, nothing is dropped
    std::vector<std::string> dropped, variables;
    for (const auto& [k, v] : change.before.items()) {
        if (!replaced.count(k) || now->param(k) || !p.params.contains(k) ||
            std::find(change.keys.begin(), change.keys.end(), k) != change.keys.end())
            continue;
        const json value = p.params[k];
        p.params.erase(k);
        dropped.push_back(k);
        if (!is_variable_ref(value)) continue;
        const std::string var = value.get<std::string>().substr(1);
        if (variable_used(g, var)) continue;
        auto it = std::find_if(g.variables.begin(), g.variables.end(), [&](const VariableDecl& x) { return x.name == var; });
        if (it != g.variables.end()) g.variables.erase(it), variables.push_back(var);
    }
    if (dropped.empty()) return;
    std::string note = change.by + ": pass '" + p.name + "': " + join(swaps) +
                       ", so the parameters set for the replaced hook are dropped: " + join(dropped);
    if (!variables.empty())
        note += " (and the graph variable" + std::string(variables.size() > 1 ? "s" : "") + " that fed only them: " +
                join(variables) + ")";
    g.notes.push_back(note);
}

const GraphFile& settle_pending_swaps(const GraphFile& g, const PassRegistry& reg, std::optional<GraphFile>& copy) {
    if (std::none_of(g.passes.begin(), g.passes.end(), [](const PassDecl& p) { return !p.changes.empty(); })) return g;
    copy = g;
    settle_hook_swaps(*copy, reg);
    return *copy;
}

}  // namespace graph_detail

void settle_hook_swaps(GraphFile& g, const PassRegistry& reg) {
    for (auto& p : g.passes) {
        const PassTypeInfo* t = reg.find(p.type);
        if (t)
            for (const auto& c : p.changes) swap_hook_params(g, p, *t, c);
        p.changes.clear();
    }
}

}  // namespace pathlet
