// compile_graph: validated file -> what runs. Enabled passes, culling (with reasons), a stable
// topological order, resolved resources and parameters, lifetimes; then pooling (graph_pool.cpp).
#include "graph_internal.hpp"

#include <algorithm>
#include <queue>
#include <set>

namespace pathlet {

using namespace graph_detail;

namespace {

// Why a pass that reaches no output was dropped, naming its outputs and who reads them.
std::string cull_reason(const GraphIndex& idx, int pass) {
    std::vector<std::string> outs;
    std::set<std::string> readers;
    for (const auto& b : idx.outputs[pass]) {
        if (b.resource < 0) continue;
        outs.push_back(idx.resources[b.resource].name);
        for (size_t j = 0; j < idx.inputs.size(); ++j)
            for (const auto& in : idx.inputs[j])
                if (in.resource == b.resource && int(j) != pass) readers.insert(idx.g->passes[j].name);
    }
    if (outs.empty()) return "has no outputs";
    const std::string list = (outs.size() == 1 ? "output " : "outputs ") + join(outs);
    const char* verb = outs.size() == 1 ? " is" : " are";
    if (readers.empty()) return list + verb + " never read and not captured";
    return list + verb + " read only by culled passes (" + join({readers.begin(), readers.end()}) + ")";
}

}  // namespace

CompiledGraph compile_graph(const GraphFile& g, const PassRegistry& reg, glm::ivec2 output_size) {
    std::vector<Diagnostic> diags;
    GraphIndex idx = build_index(g, reg, diags);
    validate_index(idx, diags);
    if (output_size.x < 1 || output_size.y < 1)
        diags.push_back({g.path, "", "output size must be positive, got " + std::to_string(output_size.x) + "x" +
                                         std::to_string(output_size.y)});
    if (!diags.empty()) throw GraphError(std::move(diags));

    CompiledGraph cg;
    cg.file = g.path;
    cg.name = g.name;
    cg.output_size = output_size;
    cg.dirs = g.dirs;
    cg.instance_types = idx.instance_types;
    for (const auto& v : g.variables) cg.variables[v.name] = v.value;

    const size_t np = g.passes.size();
    std::vector<char> enabled(np, 1);
    for (size_t i = 0; i < np; ++i) {
        bool e = true;
        resolve_enabled(g, g.passes[i].enabled, e);  // validated above
        enabled[i] = e;
    }

    // A disabled writer leaves optional readers unbound; required readers and outputs are errors.
    std::vector<std::vector<BoundPin>> inputs = idx.inputs;
    for (size_t i = 0; i < np; ++i) {
        if (!enabled[i]) continue;
        auto& ins = inputs[i];
        for (auto it = ins.begin(); it != ins.end();) {
            int w = idx.writer(it->resource);
            if (w < 0 || enabled[w]) {
                ++it;
                continue;
            }
            if (!it->decl->optional)
                diags.push_back({g.path, it->pointer, "input '" + it->pin + "' reads '" + idx.resources[it->resource].name +
                                                          "', but its writer '" + g.passes[w].name + "' is disabled"});
            it = ins.erase(it);
        }
    }
    std::vector<int> output_res;
    for (const auto& o : g.outputs) {
        std::string err;
        int r = idx.resolve(o.resource, err, /*allow_internal=*/true);
        int w = idx.writer(r);
        if (w >= 0 && !enabled[w])
            diags.push_back({g.path, o.pointer + "/resource", "output '" + o.resource + "' is written by pass '" +
                                                                  g.passes[w].name + "', which is disabled"});
        output_res.push_back(r);
    }
    if (!diags.empty()) throw GraphError(std::move(diags));

    // Keep what an output needs, walking back through this frame's and last frame's reads
    // (a pass reading "x@prev" needs x's writer to run so that next frame has it).
    std::vector<char> keep(np, 0);
    std::vector<int> work;
    auto need = [&](int r) {
        int w = idx.writer(r);
        if (w >= 0 && !keep[w]) keep[w] = 1, work.push_back(w);
    };
    for (int r : output_res) need(r);
    // Side-effect passes (captures, statistics) are roots too: their work is outside the graph.
    for (size_t i = 0; i < np; ++i)
        if (enabled[i] && idx.types[i] && idx.types[i]->side_effect && !keep[i]) keep[i] = 1, work.push_back(int(i));
    while (!work.empty()) {
        int p = work.back();
        work.pop_back();
        for (const auto& b : inputs[p]) need(b.resource);
    }
    for (size_t i = 0; i < np; ++i) {
        if (!enabled[i]) cg.culled.push_back({g.passes[i].name, "disabled"});
        else if (!keep[i]) cg.culled.push_back({g.passes[i].name, cull_reason(idx, int(i))});
    }

    // Topological order (Kahn); among ready passes the earliest in the file runs first.
    std::vector<std::vector<int>> deps = pass_dependencies(idx), users(np);
    std::vector<int> pending(np, 0);
    for (size_t i = 0; i < np; ++i) {
        if (!keep[i]) continue;
        for (int d : deps[i])
            if (keep[d]) users[d].push_back(int(i)), ++pending[i];
    }
    std::priority_queue<int, std::vector<int>, std::greater<int>> ready;
    for (size_t i = 0; i < np; ++i)
        if (keep[i] && !pending[i]) ready.push(int(i));
    std::vector<int> order, position(np, -1);
    while (!ready.empty()) {
        int p = ready.top();
        ready.pop();
        position[p] = int(order.size());
        order.push_back(p);
        for (int u : users[p])
            if (--pending[u] == 0) ready.push(u);
    }
    const int last = int(order.size()) - 1;

    // Lifetimes over the order: writer to last reader; history and persistent resources live
    // the whole frame; outputs until the end (presented/captured after the last pass).
    std::vector<int> first(idx.resources.size(), -1), lastuse(idx.resources.size(), -1);
    auto use = [&](int r, int at) {
        first[r] = first[r] < 0 ? at : std::min(first[r], at);
        lastuse[r] = std::max(lastuse[r], at);
    };
    for (int p : order) {
        for (const auto& b : inputs[p]) use(b.resource, position[p]);
        for (const auto& b : idx.outputs[p]) use(b.resource, position[p]);
    }
    std::set<int> captured(output_res.begin(), output_res.end());
    for (size_t r = 0; r < idx.resources.size(); ++r) {
        if (captured.count(int(r)) && first[r] < 0) use(int(r), 0);  // a persistent output nobody writes
        if (first[r] < 0) continue;
        if (idx.resources[r].history || idx.resources[r].persistent) first[r] = 0, lastuse[r] = last;
        if (captured.count(int(r))) lastuse[r] = last;
    }

    // Compiled resources: the used ones, ordered by first use (then declaration).
    std::vector<int> used;
    for (size_t r = 0; r < idx.resources.size(); ++r)
        if (first[r] >= 0) used.push_back(int(r));
    std::stable_sort(used.begin(), used.end(), [&](int a, int b) { return first[a] < first[b]; });
    std::vector<int> compiled_index(idx.resources.size(), -1);
    // Resolved parameters: defaults + graph + variables + --set (buffers may be sized by them).
    std::vector<json> params(np);
    for (int p : order) {
        params[p] = idx.types[p]->default_params();
        for (const auto& [k, v] : g.passes[p].params.items()) resolve_param(g, *idx.types[p]->param(k), v, params[p][k]);
    }
    for (int r : used) {
        const ResourceDecl& d = idx.resources[r];
        const PinDecl* pin = idx.writer_pin(r);
        CompiledResource c;
        c.name = d.name;
        c.kind = d.kind;
        c.history = d.history;
        c.persistent = d.persistent;
        c.captured = captured.count(r) > 0;
        c.first_use = first[r];
        c.last_use = lastuse[r];
        if (d.kind == PinKind::Texture) {
            c.format = idx.resolved_format(r);
            const FormatInfo* f = find_format(c.format);
            glm::ivec2 size;
            resolve_size(idx, r, output_size, size);  // validated above
            c.width = size.x;
            c.height = size.y;
            c.mips = d.mips >= 0 ? d.mips : pin ? pin->mips : 1;
            if (c.mips == 0) c.mips = full_mip_count(c.width, c.height);
            c.mips = std::min(c.mips, full_mip_count(c.width, c.height));
            c.internal_format = f ? f->internal_format : 0;
            c.bytes = f ? texture_bytes(*f, c.width, c.height, c.mips) : 0;
        } else {
            const size_t pixels = size_t(output_size.x) * size_t(output_size.y);
            if (d.bytes) c.bytes = d.bytes;
            else if (d.bytes_per_pixel) c.bytes = d.bytes_per_pixel * pixels;
            else if (pin && pin->bytes_from_params && !params[idx.writer(r)].is_null())
                c.bytes = pin->bytes_from_params(params[idx.writer(r)]);
            else if (pin && pin->bytes) c.bytes = pin->bytes;
            else if (pin) c.bytes = pin->bytes_per_pixel * pixels;
            c.width = c.height = 0;
        }
        compiled_index[r] = int(cg.resources.size());
        cg.resources.push_back(std::move(c));
    }

    // Passes in execution order, with resolved parameters and bindings.
    for (int p : order) {
        const PassDecl& d = g.passes[p];
        CompiledPass c;
        c.name = d.name;
        c.type = idx.types[p];
        c.pointer = d.pointer;
        c.params = params[p];
        for (const auto& b : inputs[p]) c.bindings[b.pin] = {compiled_index[b.resource], b.prev};
        for (const auto& b : idx.outputs[p]) {
            c.bindings[b.pin] = {compiled_index[b.resource], false};
            cg.resources[compiled_index[b.resource]].writer = int(cg.passes.size());
        }
        cg.passes.push_back(std::move(c));
    }

    for (size_t i = 0; i < g.outputs.size(); ++i) {
        OutputDecl o = g.outputs[i];
        o.resource = idx.resources[output_res[i]].name;
        cg.outputs.push_back(o);
    }

    assign_slots(cg);
    return cg;
}

}  // namespace pathlet
