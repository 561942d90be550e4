// apply_overrides: "--set name=value" (graph variable) and "--set pass.param=value" (one pass's
// parameter, read by the parameter's declared type). "--set pass.enabled=false" toggles a pass
// and "--set pass.type=TYPE" replaces its type (the parameters it had stay and are validated
// against the new type), unless the type has a parameter of that name. Each set is a layer after
// the graph files', applied in order; a set that changes a hook (PASS.color_hook, or a variable
// a hook parameter takes) is recorded as a replacement of that hook. The hooks then resolve once
// (graph_hooks.cpp), and a set of a hook's own parameter is read against the hook in place after
// every set. A hook may be a path the user gave (user_files: the command line, Python), never
// one an experiment file or viewer script gives.
#include "graph_internal.hpp"

#include <algorithm>

namespace pathlet {

using namespace graph_detail;

namespace {

bool parse_bool(const std::string& s, bool& out) {
    if (s == "true" || s == "1" || s == "on" || s == "yes") return out = true, true;
    if (s == "false" || s == "0" || s == "off" || s == "no") return out = false, true;
    return false;
}

// The hook names the passes give now: pass index -> hook parameter -> name ("" = the default).
std::vector<std::map<std::string, std::string>> hook_names_of(const GraphFile& g) {
    std::vector<std::map<std::string, std::string>> out;
    for (const PassDecl& p : g.passes) {
        auto& names = out.emplace_back();
        for (const HookRole role : kHookRoles) {
            const char* param = hook_role(role).param;
            std::string name;
            if (p.params.contains(param) && p.params[param].is_string()) {
                name = p.params[param].get<std::string>();
                if (is_variable_ref(p.params[param]))
                    if (const VariableDecl* v = find_variable(g, name.substr(1)); v && v->value.is_string())
                        name = v->value.get<std::string>();
            }
            names[param] = name;
        }
    }
    return out;
}

// The hooks a set replaced, recorded as swaps of its layer.
void record_swaps(GraphFile& g, const std::vector<std::map<std::string, std::string>>& before, int layer,
                  const std::string& set) {
    const auto after = hook_names_of(g);
    for (size_t i = 0; i < g.passes.size(); ++i)
        for (const auto& [param, name] : after[i])
            if (before[i].at(param) != name) g.passes[i].swaps.push_back({param, layer, "--set " + set, before[i].at(param), name});
}

// A set of a parameter no registry type declares: read once the hooks are known.
struct HookParamSet {
    size_t pass;
    std::string param, text, set;
    int layer;
};

}  // namespace

void apply_overrides(GraphFile& g, const std::vector<std::string>& sets, const PassRegistry& reg,
                     std::vector<Diagnostic>& diags, const std::set<std::string>& user_files) {
    g.user_files.insert(user_files.begin(), user_files.end());
    std::vector<HookParamSet> later;
    for (const auto& set : sets) {
        auto error = [&](const std::string& ptr, const std::string& msg) {
            diags.push_back({g.path, ptr, "--set " + set + ": " + msg});
        };
        const int layer = g.layers++;
        const size_t eq = set.find('=');
        if (eq == std::string::npos || eq == 0) {
            error("", "expected name=value (a variable) or pass.param=value");
            continue;
        }
        const std::string lhs = set.substr(0, eq), text = set.substr(eq + 1);
        const size_t dot = lhs.find('.');

        if (dot == std::string::npos) {
            auto it = std::find_if(g.variables.begin(), g.variables.end(), [&](const auto& v) { return v.name == lhs; });
            if (it == g.variables.end()) {
                error("/variables", "unknown variable '" + lhs + "'" + did_you_mean(lhs, variable_names(g)) +
                                        (g.variables.empty() ? "; the graph declares no variables"
                                                             : "; its variables: " + join(variable_names(g))) +
                                        "; use pass.param=value for a pass parameter");
                continue;
            }
            json out;
            if (std::string err = it->decl.coerce_text(text, out); !err.empty()) {
                error(it->pointer, "variable '" + lhs + "' " + err);
                continue;
            }
            const auto before = hook_names_of(g);
            it->value = out;
            it->set_by = set;
            record_swaps(g, before, layer, set);
            continue;
        }

        const std::string pass = lhs.substr(0, dot), param = lhs.substr(dot + 1);
        auto p = std::find_if(g.passes.begin(), g.passes.end(), [&](const auto& x) { return x.name == pass; });
        if (p == g.passes.end()) {
            std::vector<std::string> names;
            for (const auto& x : g.passes) names.push_back(x.name);
            error("/passes", "unknown pass '" + pass + "'" + did_you_mean(pass, names));
            continue;
        }
        const PassTypeInfo* t = reg.find(p->type);
        if (param == "type" && (!t || !t->param("type"))) {
            if (!reg.find(text)) {
                error(p->pointer + "/type", "unknown pass type '" + text + "'" + did_you_mean(text, reg.names()));
                continue;
            }
            p->type = text;
            continue;
        }
        if (!t) {
            error(p->pointer + "/type", "pass '" + pass + "' has unknown type '" + p->type + "'");
            continue;
        }
        const ParamDecl* d = t->param(param);
        if (!d && param == "enabled") {
            bool on = true;
            if (parse_bool(text, on)) p->enabled = on;
            else error(p->pointer + "/enabled", "enabled must be true or false, got '" + text + "'");
            continue;
        }
        if (!d) {  // perhaps a hook's parameter
            later.push_back({size_t(p - g.passes.begin()), param, text, set, layer});
            continue;
        }
        json out;
        if (std::string err = d->coerce_text(text, out); !err.empty()) {
            error(p->pointer + "/params/" + pointer_escape(param), "parameter '" + param + "' " + err);
            continue;
        }
        const auto before = hook_names_of(g);
        p->params[param] = out;
        p->written[param] = layer;
        if (d->hook) record_swaps(g, before, layer, set);
    }

    g.hooks_resolved = false;
    resolve_hooks(g, reg);
    for (const HookParamSet& s : later) {
        PassDecl& p = g.passes[s.pass];
        const PassTypeInfo& t = *p.instance_type;
        const ParamDecl* d = t.param(s.param);
        if (!d) {
            // A hook that could not be read is reported at its place; its parameters are unknown.
            if (std::any_of(g.hook_problems.begin(), g.hook_problems.end(),
                            [&](const Diagnostic& x) { return x.pointer.rfind(p.pointer + "/", 0) == 0; }))
                continue;
            std::vector<std::string> names;
            for (const auto& x : t.params) names.push_back(x.name);
            diags.push_back({g.path, p.pointer + "/params",
                             "--set " + s.set + ": unknown parameter '" + s.param + "' for pass type '" + t.type + "'" +
                                 did_you_mean(s.param, names) +
                                 "; its parameters: " + (names.empty() ? std::string("none") : join(names))});
            continue;
        }
        json out;
        if (std::string err = d->coerce_text(s.text, out); !err.empty()) {
            diags.push_back({g.path, p.pointer + "/params/" + pointer_escape(s.param),
                             "--set " + s.set + ": parameter '" + s.param + "' " + err});
            continue;
        }
        p.params[s.param] = out;
        p.written[s.param] = s.layer;
    }
}

}  // namespace pathlet
