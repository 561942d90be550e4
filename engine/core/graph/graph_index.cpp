// Name resolution: pass types, declared + implicit resources, pin bindings, writers.
#include "graph_internal.hpp"
#include "../plugin_trust.hpp"

#include <filesystem>

namespace pathlet::graph_detail {

Ref split_ref(const std::string& text) {
    static const std::string suffix = "@prev";
    if (text.size() > suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0)
        return {text.substr(0, text.size() - suffix.size()), true};
    return {text, false};
}

int GraphIndex::find_resource(const std::string& name) const {
    auto it = resource_by_name.find(name);
    return it == resource_by_name.end() ? -1 : it->second;
}

std::vector<std::string> GraphIndex::resource_names() const {
    std::vector<std::string> v;
    for (const auto& r : resources) v.push_back(r.name);
    return v;
}

int GraphIndex::resolve(const std::string& ref, std::string& err, bool allow_internal) const {
    err.clear();
    if (int r = find_resource(ref); r >= 0) {
        if (!resources[r].internal || allow_internal) return r;
        err = "'" + ref + "' is a pass's internal texture (its own, allocated by the engine); no other pass reads it";
        return -1;
    }
    const size_t dot = ref.find('.');
    if (dot == std::string::npos) {
        err = "unknown resource '" + ref + "'" + did_you_mean(ref, resource_names());
        return -1;
    }
    const std::string pass = ref.substr(0, dot), pin = ref.substr(dot + 1);
    auto it = pass_by_name.find(pass);
    if (it == pass_by_name.end()) {
        std::vector<std::string> passes;
        for (const auto& p : g->passes) passes.push_back(p.name);
        err = "'" + ref + "' names no resource and no pass '" + pass + "'" + did_you_mean(pass, passes);
        return -1;
    }
    const PassTypeInfo* t = types[it->second];
    if (!t) return -1;  // unknown type: reported at its "type"
    const PinDecl* pd = t->pin(pin);
    if (!pd || pd->dir != PinDir::Output) {
        std::vector<std::string> outs;
        for (const auto& p : t->pins)
            if (p.dir == PinDir::Output && !p.internal) outs.push_back(p.name);
        err = "pass '" + pass + "' (type '" + t->type + "') has no output pin '" + pin + "'" + did_you_mean(pin, outs) +
              "; its outputs: " + (outs.empty() ? std::string("none") : join(outs));
        return -1;
    }
    // Bound output: the resource it names (an unknown one was reported at the binding).
    auto bound = g->passes[it->second].outputs.find(pin);
    if (bound != g->passes[it->second].outputs.end()) return find_resource(bound->second);
    return -1;  // unreachable: unbound outputs have implicit resources found above
}

const PinDecl* GraphIndex::writer_pin(int r) const {
    return writers[r].empty() ? nullptr : writers[r][0].second->decl;
}

std::string GraphIndex::resolved_format(int r) const {
    if (!resources[r].format.empty()) return resources[r].format;
    const PinDecl* p = writer_pin(r);
    return p && p->kind == PinKind::Texture && p->format != "any" ? p->format : "";
}

// Where plugins were looked for, and the three ways to add a folder.
std::string unknown_type_hint(const PassRegistry& reg) {
    std::string dirs = reg.searched_dirs().empty() ? std::string("(no folder)") : join(reg.searched_dirs(), ", ");
    return "; no plugin on the search path provides it (searched: " + dirs +
           "). Add the folder holding its .so with --plugin-dir DIR, PATHLET_PLUGIN_PATH=DIR[:DIR...], or "
           "\"plugin_dirs\": [\"DIR\"] in the graph (relative to the graph file; loaded once trusted: pathlet trust DIR)";
}

// The type may well come from a plugin folder of the graph that was not loaded: say so, with
// the command that trusts it, instead of suggesting a typo.
std::string untrusted_hint(const std::vector<GraphFile::UntrustedDir>& dirs) {
    std::string s = "; it may come from the graph's plugin folder";
    for (size_t i = 0; i < dirs.size(); ++i) {
        std::vector<std::string> names;
        for (const auto& f : dirs[i].files) names.push_back(std::filesystem::path(f).filename().string());
        s += std::string(i ? "; or " : " ") + dirs[i].dir + " (" + join(names) + "), not loaded because it is not trusted: " +
             trust_command(dirs[i].dir);
    }
    return s + " trusts it (--trust-graph-plugins: for one run)";
}

// Pass i's bindings: each bound pin checked against its type's declaration and resolved to a
// resource, then its unbound outputs' implicit resources.
static void bind_pins(GraphIndex& idx, size_t i, std::vector<Diagnostic>& diags) {
    const GraphFile& g = *idx.g;
    auto error = [&](const std::string& ptr, const std::string& msg) { diags.push_back({g.path, ptr, msg}); };
    const PassDecl& p = g.passes[i];
    const PassTypeInfo* t = idx.types[i];
    if (!t) return;  // unknown type: reported with its "type"
    auto pins_of = [&](PinDir dir) {
        std::vector<std::string> v;
        for (const auto& pin : t->pins)
            if (pin.dir == dir && !pin.internal) v.push_back(pin.name);
        return v;
    };
    for (const bool input : {true, false}) {
        const PinDir dir = input ? PinDir::Input : PinDir::Output;
        const char* key = input ? "inputs" : "outputs";
        for (const auto& [pin, ref] : input ? p.inputs : p.outputs) {
            BoundPin b;
            b.pin = pin;
            b.pointer = p.pointer + "/" + key + "/" + pointer_escape(pin);
            const PinDecl* pd = t->pin(pin);
            if (pd && pd->internal) {
                error(b.pointer, "'" + pin + "' is " + t->type + "'s internal " + std::string(pd->kind == PinKind::Texture ? "texture" : "buffer") + " (the pass's own, allocated by "
                                 "the engine): graphs do not bind it; remove this binding");
                pd = nullptr;
            } else if (!pd || pd->dir != dir) {
                std::string msg = "pass type '" + t->type + "' has no " + (input ? "input" : "output") + " pin '" + pin + "'";
                if (pd) msg += "; '" + pin + "' is an " + (input ? "output: bind it under \"outputs\"" : "input: bind it under \"inputs\"");
                else msg += did_you_mean(pin, pins_of(dir));
                auto names = pins_of(dir);
                msg += std::string("; its ") + key + ": " + (names.empty() ? std::string("none") : join(names));
                error(b.pointer, msg);
            } else {
                b.decl = pd;
            }
            std::string err;
            if (input) {
                Ref r = split_ref(ref);
                b.prev = r.prev;
                b.resource = idx.resolve(r.name, err);
            } else if ((b.resource = idx.find_resource(ref)) < 0) {
                err = "unknown resource '" + ref + "'" + did_you_mean(ref, idx.resource_names()) +
                      "; declare it under /resources, or leave the pin unbound to get '" + p.name + "." + pin + "'";
            }
            if (!err.empty()) error(b.pointer, err);
            (input ? idx.inputs : idx.outputs)[i].push_back(b);
        }
    }
    for (const auto& pin : t->pins) {
        if (pin.dir != PinDir::Output || p.outputs.count(pin.name) || pin.optional) continue;
        int r = idx.find_resource(p.name + "." + pin.name);
        // A duplicate pass name shares the first pass's implicit names: reported, not bound twice.
        if (r >= 0 && idx.resources[r].implicit && idx.resources[r].pointer == p.pointer)
            idx.outputs[i].push_back({pin.name, &pin, r, false, p.pointer});
    }
}

GraphIndex build_index(const GraphFile& g, const PassRegistry& reg, std::vector<Diagnostic>& diags) {
    GraphIndex idx;
    idx.g = &g;
    idx.reg = &reg;
    auto error = [&](const std::string& ptr, const std::string& msg) { diags.push_back({g.path, ptr, msg}); };

    diags.insert(diags.end(), g.hook_problems.begin(), g.hook_problems.end());
    idx.resources = g.resources;
    for (size_t r = 0; r < g.resources.size(); ++r) idx.resource_by_name[g.resources[r].name] = int(r);

    for (size_t i = 0; i < g.passes.size(); ++i) {
        const PassDecl& p = g.passes[i];
        idx.pass_by_name.emplace(p.name, int(i));
        // Its instance type: with the parameters of its hooks (resolve_hooks).
        const PassTypeInfo* t = p.instance_type ? p.instance_type.get() : reg.find(p.type);
        if (p.instance_type) idx.instance_types.push_back(p.instance_type);
        idx.types.push_back(t);
        if (!t) {
            error(p.pointer + "/type", "unknown pass type '" + p.type + "'" +
                                           (g.untrusted_plugin_dirs.empty()
                                                ? did_you_mean(p.type, reg.names()) + unknown_type_hint(reg)
                                                : untrusted_hint(g.untrusted_plugin_dirs)));
            continue;
        }
        // Unbound outputs get an implicit resource "<pass>.<pin>" shaped by the pin; unbound
        // optional outputs get none (the pass sees connected() == false and skips them).
        for (const auto& pin : t->pins) {
            if (pin.dir != PinDir::Output || p.outputs.count(pin.name) || pin.optional) continue;
            ResourceDecl r;
            r.name = p.name + "." + pin.name;
            r.kind = pin.kind;
            r.implicit = true;
            r.internal = pin.internal;
            r.persistent = pin.persistent;  // an internal resource the pass keeps across frames
            r.pointer = p.pointer;
            if (idx.resource_by_name.emplace(r.name, int(idx.resources.size())).second) idx.resources.push_back(r);
        }
    }

    idx.inputs.resize(g.passes.size());
    idx.outputs.resize(g.passes.size());
    for (size_t i = 0; i < g.passes.size(); ++i) bind_pins(idx, i, diags);

    // Writers, once every vector above has its final size (the BoundPin pointers stay valid).
    idx.writers.resize(idx.resources.size());
    for (size_t i = 0; i < g.passes.size(); ++i)
        for (const auto& b : idx.outputs[i])
            if (b.resource >= 0 && b.decl) idx.writers[b.resource].push_back({int(i), &b});
    return idx;
}

}  // namespace pathlet::graph_detail
