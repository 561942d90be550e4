// apply_overrides: "--set name=value" (graph variable) and "--set pass.param=value" (one pass's
// parameter, read by the parameter's declared type, the parameters its hook files declare
// included). "--set pass.enabled=false" toggles a pass and "--set pass.type=TYPE" replaces its
// type (the parameters it had stay and are validated against the new type), unless the type
// has a parameter of that name. Overrides apply in order: a hook set first declares the
// parameters a later --set may give, and a set that replaces a hook drops the parameters the
// graph set for the replaced one (graph_hook_swap.cpp). A hook may be a path the user gave
// (user_files: the command line, Python), never one an experiment file or viewer script gives.
#include "graph_internal.hpp"

#include <algorithm>
#include <filesystem>

namespace pathlet {

using namespace graph_detail;

namespace {

bool parse_bool(const std::string& s, bool& out) {
    if (s == "true" || s == "1" || s == "on" || s == "yes") return out = true, true;
    if (s == "false" || s == "0" || s == "off" || s == "no") return out = false, true;
    return false;
}

// A variable that pass hook parameters take ("color_hook": "$color_hook" in every variant2_*
// graph) swaps each of those hooks as --set PASS.color_hook would: a path the user gave is on the
// search path, a hook that cannot be used is this set's error, and the replaced hook's
// parameters are dropped (graph_hook_swap.cpp). The variable already holds the new value.
template <class Error>
bool set_hook_variable(GraphFile& g, const std::string& var, const json& old, const std::string& text,
                       const std::string& set, const PassRegistry& reg, const std::set<std::string>& user_files,
                       const Error& error) {
    for (PassDecl& p : g.passes) {
        const PassTypeInfo* t = reg.find(p.type);
        if (!t) continue;
        for (const ParamDecl& d : t->params) {
            if (d.hook.empty() || !p.params.contains(d.name) || !is_variable_ref(p.params[d.name]) ||
                p.params[d.name].get<std::string>().substr(1) != var)
                continue;
            if (std::filesystem::path(text).is_absolute() && user_files.count(text) &&
                std::find(g.dirs.begin(), g.dirs.end(), text) == g.dirs.end())
                g.dirs.push_back(text);
            PassDecl::ParamsChange change{"--set " + set, p.params, {d.name}};
            change.before[d.name] = old;
            std::string bad, bad_at;
            pass_instance_type(g, p, *t, bad, bad_at);
            if (!bad.empty()) {
                error(p.pointer + "/params/" + pointer_escape(d.name), bad);
                return false;
            }
            swap_hook_params(g, p, *t, change);
        }
    }
    return true;
}

}  // namespace

void apply_overrides(GraphFile& g, const std::vector<std::string>& sets, const PassRegistry& reg,
                     std::vector<Diagnostic>& diags, const std::set<std::string>& user_files) {
    settle_hook_swaps(g, reg);
    for (const auto& set : sets) {
        auto error = [&](const std::string& ptr, const std::string& msg) {
            diags.push_back({g.path, ptr, "--set " + set + ": " + msg});
        };
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
            const json old = it->value;
            it->value = out;
            if (!set_hook_variable(g, lhs, old, text, set, reg, user_files, error)) it->value = old;
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
        const PassTypeInfo* reg_type = reg.find(p->type);
        if (param == "type" && (!reg_type || !reg_type->param("type"))) {
            if (!reg.find(text)) {
                error(p->pointer + "/type", "unknown pass type '" + text + "'" + did_you_mean(text, reg.names()));
                continue;
            }
            p->type = text;
            continue;
        }
        if (!reg_type) {
            error(p->pointer + "/type", "pass '" + pass + "' has unknown type '" + p->type + "'");
            continue;
        }
        std::string hook_err, hook_at;
        const auto inst = pass_instance_type(g, *p, *reg_type, hook_err, hook_at);
        if (!hook_err.empty()) {
            error(hook_at, hook_err);
            continue;
        }
        const PassTypeInfo* t = inst.get();
        const ParamDecl* d = t->param(param);
        if (!d && param == "enabled") {
            bool on = true;
            if (parse_bool(text, on)) p->enabled = on;
            else error(p->pointer + "/enabled", "enabled must be true or false, got '" + text + "'");
            continue;
        }
        if (!d) {
            std::vector<std::string> names;
            for (const auto& x : t->params) names.push_back(x.name);
            error(p->pointer + "/params", "unknown parameter '" + param + "' for pass type '" + t->type + "'" +
                                              did_you_mean(param, names) +
                                              "; its parameters: " + (names.empty() ? std::string("none") : join(names)));
            continue;
        }
        json out;
        if (std::string err = d->coerce_text(text, out); !err.empty()) {
            error(p->pointer + "/params/" + pointer_escape(param), "parameter '" + param + "' " + err);
            continue;
        }
        if (d->hook.empty()) {
            p->params[param] = out;
            continue;
        }
        // A hook file the user named by its path: on the search path as that file alone.
        if (std::filesystem::path(text).is_absolute() && user_files.count(text) &&
            std::find(g.dirs.begin(), g.dirs.end(), text) == g.dirs.end())
            g.dirs.push_back(text);
        const PassDecl::ParamsChange change{"--set " + set, p->params, {param}};
        p->params[param] = out;
        // A hook that cannot be used is this set's error, before any work (a bench checks its
        // graphs and sets before the first run).
        std::string bad, bad_at;
        pass_instance_type(g, *p, *reg_type, bad, bad_at);
        if (!bad.empty()) {
            error(p->pointer + "/params/" + pointer_escape(param), bad);
            p->params = change.before;
            continue;
        }
        swap_hook_params(g, *p, *reg_type, change);
    }
}

}  // namespace pathlet
