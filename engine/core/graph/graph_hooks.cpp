// A hook is one value with its own parameters. Each pass's hooks resolve once, after the graph
// files and every --set: the file is found and read for its @param lines, and the pass's
// instance type is its registry type plus those parameters. A parameter is stamped with the
// layer that wrote it (the graph files of the extends chain, then each --set) and every
// replacement of a hook with its layer, so a parameter set before its hook was replaced is
// known to be the replaced hook's: where the new hook lacks it, it is dropped with a note (and
// so are the graph variables that fed only it). A parameter set at or after the replacement is
// meant for the new hook: where the new hook lacks it, validation names it with a did-you-mean.
#include "graph_internal.hpp"
#include "hook_params.hpp"

#include <algorithm>
#include <filesystem>

namespace pathlet {

using namespace graph_detail;

namespace {

std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

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

// The pass's hooks: found and read, and its instance type. A problem goes to g.hook_problems
// at the parameter that names the hook (or the pass's type, for its default hook).
bool bind_hooks(GraphFile& g, PassDecl& p, const PassTypeInfo& t) {
    p.hooks.clear();
    for (const ParamDecl& d : t.params) {
        if (!d.hook) continue;
        const bool set = p.params.contains(d.name);
        json name = d.def;
        if (set && !resolve_param(g, d, p.params[d.name], name).empty()) continue;  // validation names it
        if (!name.is_string() || name.get<std::string>().empty()) continue;       // the kit's default
        try {
            p.hooks.push_back(bind_hook(t, *d.hook, name.get<std::string>(), g.dirs, g.user_files));
        } catch (const HookError& e) {
            g.hook_problems.push_back({g.path, p.pointer + (set ? "/params/" + pointer_escape(d.name) : "/type"), e.what()});
            return false;
        }
    }
    try {
        p.instance_type = instance_type(t, p.hooks);
    } catch (const HookError& e) {
        g.hook_problems.push_back({g.path, p.pointer + "/type", e.what()});
        return false;
    }
    return true;
}

// The parameters of `p` set for a hook that was replaced after they were written and that the
// pass's hooks now lack: dropped, with a note naming the last replacement.
void drop_replaced_hooks_params(GraphFile& g, PassDecl& p, const PassTypeInfo& t) {
    std::vector<std::string> dropped;
    const PassDecl::HookSwap* last = nullptr;
    for (const auto& [key, value] : p.params.items()) {
        if (p.instance_type->param(key)) continue;
        const auto w = p.written.find(key);
        const int written = w == p.written.end() ? 0 : w->second;
        for (const auto& s : p.swaps)
            if (s.layer > written && (!last || s.layer >= last->layer)) last = &s;
        if (std::any_of(p.swaps.begin(), p.swaps.end(), [&](const auto& s) { return s.layer > written; }))
            dropped.push_back(key);
    }
    if (dropped.empty()) return;
    std::vector<std::string> variables;
    for (const auto& key : dropped) {
        const json value = p.params[key];
        p.params.erase(key);
        if (!is_variable_ref(value)) continue;
        const std::string var = value.get<std::string>().substr(1);
        if (variable_used(g, var)) continue;
        auto it = std::find_if(g.variables.begin(), g.variables.end(), [&](const VariableDecl& x) { return x.name == var; });
        if (it == g.variables.end()) continue;
        if (!it->set_by.empty())  // the user set it for nothing
            g.hook_problems.push_back({g.path, it->pointer, "--set " + it->set_by + ": variable '" + var +
                                                                "' feeds only '" + p.name + "." + key +
                                                                "', a parameter of the hook " + last->param +
                                                                " replaced; the new hook has no such parameter"});
        g.variables.erase(it);
        variables.push_back(var);
    }
    const ParamDecl* d = t.param(last->param);
    auto shown = [&](const std::string& name, const char* none) {
        const std::string n = !name.empty() ? name : d && d->def.is_string() ? d->def.get<std::string>() : "";
        return n.empty() ? std::string(none) : quoted(file_name(n));
    };
    std::string note = last->by + ": pass '" + p.name + "': " + last->param + " " + shown(last->after, "(the kit's default)") +
                       " replaces " + shown(last->before, "the kit's default") +
                       ", so the parameters set for the replaced hook are dropped: " + join(dropped);
    if (!variables.empty())
        note += " (and the graph variable" + std::string(variables.size() > 1 ? "s" : "") + " that fed only them: " +
                join(variables) + ")";
    g.notes.push_back(note);
}

}  // namespace

void resolve_hooks(GraphFile& g, const PassRegistry& reg) {
    if (g.hooks_resolved) return;
    g.hook_problems.clear();
    for (PassDecl& p : g.passes) {
        p.instance_type.reset();
        const PassTypeInfo* t = reg.find(p.type);
        if (!t) continue;  // validation names it
        if (bind_hooks(g, p, *t)) {
            drop_replaced_hooks_params(g, p, *t);
        } else {
            p.hooks.clear();
            p.instance_type = std::shared_ptr<const PassTypeInfo>(t, [](const PassTypeInfo*) {});
        }
    }
    g.hooks_resolved = true;
}

namespace graph_detail {

const GraphFile& with_hooks_resolved(const GraphFile& g, const PassRegistry& reg, std::optional<GraphFile>& copy) {
    if (g.hooks_resolved) return g;
    copy = g;
    resolve_hooks(*copy, reg);
    return *copy;
}

}  // namespace graph_detail

}  // namespace pathlet
