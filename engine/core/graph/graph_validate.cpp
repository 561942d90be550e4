// validate_graph: every rule a graph must satisfy before anything is allocated. Collects all
// problems, each with the file and the JSON pointer of the offending value.
#include "graph_internal.hpp"

#include <algorithm>
#include <functional>
#include <set>

namespace pathlet {

using namespace graph_detail;

namespace graph_detail {

std::vector<std::vector<int>> pass_dependencies(const GraphIndex& idx) {
    std::vector<std::vector<int>> deps(idx.inputs.size());
    for (size_t i = 0; i < idx.inputs.size(); ++i) {
        for (const auto& b : idx.inputs[i]) {
            if (b.resource < 0 || b.prev) continue;  // last frame's content orders nothing
            int w = idx.writer(b.resource);
            if (w >= 0 && w != int(i)) deps[i].push_back(w);
        }
        std::sort(deps[i].begin(), deps[i].end());
        deps[i].erase(std::unique(deps[i].begin(), deps[i].end()), deps[i].end());
    }
    return deps;
}

namespace {

const char* kind_name(PinKind k) { return k == PinKind::Texture ? "a texture" : "a buffer"; }

// Cycles among passes: strongly connected components (Tarjan) of more than one pass; each is
// reported once, as a path through it starting at its first pass in file order.
std::vector<std::vector<int>> find_cycles(const std::vector<std::vector<int>>& deps) {
    const int n = int(deps.size());
    std::vector<int> index(n, -1), low(n, 0), comp(n, -1), stack;
    std::vector<bool> on(n, false);
    int counter = 0, ncomp = 0;
    std::function<void(int)> strong = [&](int v) {
        index[v] = low[v] = counter++;
        stack.push_back(v);
        on[v] = true;
        for (int w : deps[v]) {
            if (index[w] < 0) strong(w), low[v] = std::min(low[v], low[w]);
            else if (on[w]) low[v] = std::min(low[v], index[w]);
        }
        if (low[v] == index[v]) {
            int w;
            do {
                w = stack.back();
                stack.pop_back();
                on[w] = false;
                comp[w] = ncomp;
            } while (w != v);
            ++ncomp;
        }
    };
    for (int v = 0; v < n; ++v)
        if (index[v] < 0) strong(v);

    std::vector<std::vector<int>> cycles;
    std::vector<bool> done(ncomp, false);
    for (int start = 0; start < n; ++start) {
        int c = comp[start];
        if (done[c] || std::count(comp.begin(), comp.end(), c) < 2) continue;
        done[c] = true;
        // deps point from reader to writer; walk them and print in data-flow order (writer first).
        std::vector<int> path{start};
        std::vector<bool> seen(n, false);
        seen[start] = true;
        std::function<bool(int)> dfs = [&](int v) {
            for (int w : deps[v]) {
                if (comp[w] != c) continue;
                if (w == start) return true;
                if (seen[w]) continue;
                seen[w] = true;
                path.push_back(w);
                if (dfs(w)) return true;
                path.pop_back();
            }
            return false;
        };
        dfs(start);
        std::reverse(path.begin(), path.end());
        std::rotate(path.begin(), std::find(path.begin(), path.end(), start), path.end());
        cycles.push_back(path);
    }
    return cycles;
}

}  // namespace

void validate_index(const GraphIndex& idx, std::vector<Diagnostic>& diags) {
    const GraphFile& g = *idx.g;
    auto error = [&](const std::string& ptr, const std::string& msg) { diags.push_back({g.path, ptr, msg}); };

    // Resources bound to outputs of passes whose type is unknown: their writer exists, it just
    // could not be checked, so "no pass writes it" would only repeat the unknown-type error.
    std::set<std::string> unknown_written;
    for (size_t i = 0; i < g.passes.size(); ++i)
        if (!idx.types[i])
            for (const auto& [pin, res] : g.passes[i].outputs) unknown_written.insert(res);
    auto written_by_unknown = [&](int r) { return unknown_written.count(idx.resources[r].name) > 0; };

    for (size_t i = 0; i < g.passes.size(); ++i) {
        const PassDecl& p = g.passes[i];
        if (int first = idx.pass_by_name.at(p.name); first != int(i))
            error(p.pointer + "/name", "duplicate pass name '" + p.name + "' (first at " + g.passes[first].pointer + ")");

        bool enabled = true;
        if (std::string err = resolve_enabled(g, p.enabled, enabled); !err.empty()) error(p.pointer + "/enabled", err);

        const PassTypeInfo* t = idx.types[i];
        if (!t) continue;  // unknown type: reported by build_index; its params and pins cannot be checked

        std::vector<std::string> param_names;
        for (const auto& d : t->params) param_names.push_back(d.name);
        for (const auto& [k, v] : p.params.items()) {
            const std::string ptr = p.pointer + "/params/" + pointer_escape(k);
            const ParamDecl* d = t->param(k);
            if (!d) {
                error(ptr, "unknown parameter '" + k + "' for pass type '" + t->type + "'" + did_you_mean(k, param_names) +
                               "; its parameters: " + (param_names.empty() ? std::string("none") : join(param_names)));
                continue;
            }
            json out;
            if (std::string err = resolve_param(g, *d, v, out); !err.empty()) error(ptr, err);
        }

        std::set<int> written;
        for (const auto& b : idx.outputs[i]) {
            if (b.resource < 0 || !b.decl) continue;
            written.insert(b.resource);
            const ResourceDecl& r = idx.resources[b.resource];
            if (r.kind != b.decl->kind) {
                error(b.pointer, "pin '" + b.pin + "' writes " + kind_name(b.decl->kind) + " but '" + r.name + "' is " +
                                     kind_name(r.kind));
                continue;
            }
            if (r.kind == PinKind::Texture && !r.format.empty() && b.decl->format != "any" && b.decl->format != r.format)
                error(b.pointer, "format mismatch: pin '" + b.pin + "' of '" + t->type + "' writes " + b.decl->format +
                                     " but resource '" + r.name + "' is " + r.format);
        }

        for (const auto& b : idx.inputs[i]) {
            if (b.resource < 0 || !b.decl) continue;
            const ResourceDecl& r = idx.resources[b.resource];
            if (r.kind != b.decl->kind) {
                error(b.pointer, "pin '" + b.pin + "' takes " + kind_name(b.decl->kind) + " but '" + r.name + "' is " +
                                     kind_name(r.kind));
                continue;
            }
            if (b.prev && !r.history) {
                error(b.pointer, "'" + r.name + "@prev' reads last frame's '" + r.name +
                                     "', but it is not a history resource; add \"history\": true to it");
                continue;
            }
            if (!b.prev && written.count(b.resource)) {
                error(b.pointer, "pass '" + p.name + "' reads and writes '" + r.name +
                                     "'; one writer per resource: write a new resource, or make '" + r.name +
                                     "' a history resource and read '" + r.name + "@prev'");
                continue;
            }
            if (idx.writer(b.resource) < 0 && !r.persistent && !written_by_unknown(b.resource)) {
                error(b.pointer, "'" + r.name + "' is read but no pass writes it");
                continue;
            }
            const std::string fmt = idx.resolved_format(b.resource);
            if (r.kind == PinKind::Texture && b.decl->format != "any" && !fmt.empty() && fmt != b.decl->format)
                error(b.pointer, "format mismatch: pin '" + b.pin + "' of '" + t->type + "' takes " + b.decl->format +
                                     " but '" + r.name + "' is " + fmt);
        }

        for (const auto& pin : t->pins)
            if (pin.dir == PinDir::Input && !pin.optional && !p.inputs.count(pin.name))
                error(p.pointer + "/inputs", "required input '" + pin.name + "' of pass type '" + t->type +
                                                 "' is not connected");
    }

    // Resources: one writer each, a known format/size for what gets written.
    for (size_t r = 0; r < idx.resources.size(); ++r) {
        const ResourceDecl& res = idx.resources[r];
        const auto& ws = idx.writers[r];
        for (size_t k = 1; k < ws.size(); ++k)
            error(ws[k].second->pointer,
                  "resource '" + res.name + "' is already written by pass '" + g.passes[ws[0].first].name + "' (at " +
                      ws[0].second->pointer + "); one writer per resource: write a new resource, or use history ('" +
                      res.name + "@prev') for read-modify-write");
        // A writer of the wrong kind was reported above; its pin says nothing about this resource.
        if (!ws.empty() && ws[0].second->decl->kind != res.kind) continue;
        const std::string where = res.implicit || res.pointer.empty() ? (ws.empty() ? res.pointer : ws[0].second->pointer)
                                                                      : res.pointer;
        if (res.kind == PinKind::Texture) {
            if (!ws.empty() && idx.resolved_format(int(r)).empty())
                error(where, "format of '" + res.name + "' is unknown: pin '" + ws[0].second->pin + "' of '" +
                                 idx.types[ws[0].first]->type + "' accepts any; add \"format\" to the resource");
            if (res.size) {
                glm::ivec2 size;
                int at = -1;
                std::string err = resolve_size(idx, int(r), {1024, 1024}, size, &at);
                if (!err.empty() && at == int(r)) error(res.pointer + "/size", err);
            }
        } else if (!ws.empty() && !res.bytes && !res.bytes_per_pixel && !ws[0].second->decl->bytes &&
                   !ws[0].second->decl->bytes_per_pixel && !ws[0].second->decl->bytes_from_params) {
            error(where, "size of buffer '" + res.name + "' is unknown: add \"bytes\" or \"bytes_per_pixel\"");
        }
    }

    if (g.outputs.empty())
        error("/outputs", "the graph has no outputs, so every pass would be culled; add {\"resource\": \"...\"}");
    for (const auto& o : g.outputs) {
        const std::string ptr = o.pointer + "/resource";
        if (split_ref(o.resource).prev) {
            error(ptr, "an output cannot be last frame's content ('" + o.resource + "')");
            continue;
        }
        std::string err;
        int r = idx.resolve(o.resource, err, /*allow_internal=*/true);
        if (r < 0) {
            if (!err.empty()) error(ptr, err);
        } else if (idx.writer(r) < 0 && !idx.resources[r].persistent && !written_by_unknown(r)) {
            error(ptr, "output '" + o.resource + "' is never written by any pass");
        }
    }

    for (const auto& cycle : find_cycles(pass_dependencies(idx))) {
        std::vector<std::string> names;
        for (int p : cycle) names.push_back(g.passes[p].name);
        names.push_back(names.front());
        error(g.passes[cycle.front()].pointer, "passes form a cycle: " + join(names, " -> ") +
                                                   " (use a history resource and '@prev' to read last frame's result)");
    }
    check_agreement(idx, diags);
}

}  // namespace graph_detail

std::vector<Diagnostic> validate_graph(const GraphFile& file, const PassRegistry& reg) {
    std::optional<GraphFile> resolved;
    const GraphFile& g = with_hooks_resolved(file, reg, resolved);
    std::vector<Diagnostic> diags;
    GraphIndex idx = build_index(g, reg, diags);
    validate_index(idx, diags);
    return diags;
}

}  // namespace pathlet
