// compile_graph: validated file -> what runs, as its stages: validate, enable (a disabled
// writer's readers and outputs), cull (with reasons), order (stable topological), lifetimes,
// resolve parameters and resources (formats, sizes, bytes), passes, then pooling (graph_pool.cpp).
#include "graph_internal.hpp"
#include "hook_params.hpp"

#include <algorithm>
#include <filesystem>
#include <optional>
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

// One compilation: the index of a valid graph and what each stage finds, in stage order.
class Compilation {
public:
    Compilation(const GraphFile& g, const PassRegistry& reg, glm::ivec2 output_size)
        : g_(g), np_(g.passes.size()), output_size_(output_size), idx_(validate(g, reg, output_size)) {}

    CompiledGraph run() {
        enable();
        cull();
        order();
        lifetimes();
        resolve_params();
        CompiledGraph cg = header();
        resolve_resources(cg);
        compiled_passes(cg);
        assign_slots(cg);  // pool: transients with disjoint lifetimes share one object
        return cg;
    }

private:
    // Every rule of validate_graph, and a positive output size; GraphError with all problems.
    static GraphIndex validate(const GraphFile& g, const PassRegistry& reg, glm::ivec2 output_size) {
        std::vector<Diagnostic> diags;
        GraphIndex idx = build_index(g, reg, diags);
        validate_index(idx, diags);
        if (output_size.x < 1 || output_size.y < 1)
            diags.push_back({g.path, "", "output size must be positive, got " + std::to_string(output_size.x) + "x" +
                                             std::to_string(output_size.y)});
        if (!diags.empty()) throw GraphError(std::move(diags));
        return idx;
    }

    // Enabled passes. A disabled writer leaves optional readers unbound; required readers and
    // outputs are errors.
    void enable() {
        std::vector<Diagnostic> diags;
        enabled_.assign(np_, 1);
        for (size_t i = 0; i < np_; ++i) {
            bool e = true;
            resolve_enabled(g_, g_.passes[i].enabled, e);  // validated above
            enabled_[i] = e;
        }
        inputs_ = idx_.inputs;
        for (size_t i = 0; i < np_; ++i) {
            if (!enabled_[i]) continue;
            auto& ins = inputs_[i];
            for (auto it = ins.begin(); it != ins.end();) {
                int w = idx_.writer(it->resource);
                if (w < 0 || enabled_[w]) {
                    ++it;
                    continue;
                }
                if (!it->decl->optional)
                    diags.push_back({g_.path, it->pointer, "input '" + it->pin + "' reads '" +
                                                               idx_.resources[it->resource].name + "', but its writer '" +
                                                               g_.passes[w].name + "' is disabled"});
                it = ins.erase(it);
            }
        }
        for (const auto& o : g_.outputs) {
            std::string err;
            int r = idx_.resolve(o.resource, err, /*allow_internal=*/true);
            int w = idx_.writer(r);
            if (w >= 0 && !enabled_[w])
                diags.push_back({g_.path, o.pointer + "/resource", "output '" + o.resource + "' is written by pass '" +
                                                                       g_.passes[w].name + "', which is disabled"});
            output_res_.push_back(r);
        }
        if (!diags.empty()) throw GraphError(std::move(diags));
    }

    // Keep what an output needs, walking back through this frame's and last frame's reads (a
    // pass reading "x@prev" needs x's writer to run so that next frame has it). Side-effect
    // passes (captures, statistics) are roots too: their work is outside the graph.
    void cull() {
        keep_.assign(np_, 0);
        std::vector<int> work;
        auto need = [&](int r) {
            int w = idx_.writer(r);
            if (w >= 0 && !keep_[w]) keep_[w] = 1, work.push_back(w);
        };
        for (int r : output_res_) need(r);
        for (size_t i = 0; i < np_; ++i)
            if (enabled_[i] && idx_.types[i] && idx_.types[i]->side_effect && !keep_[i]) keep_[i] = 1, work.push_back(int(i));
        while (!work.empty()) {
            int p = work.back();
            work.pop_back();
            for (const auto& b : inputs_[p]) need(b.resource);
        }
        for (size_t i = 0; i < np_; ++i) {
            if (!enabled_[i]) culled_.push_back({g_.passes[i].name, "disabled"});
            else if (!keep_[i]) culled_.push_back({g_.passes[i].name, cull_reason(idx_, int(i))});
        }
    }

    // Topological order (Kahn); among ready passes the earliest in the file runs first.
    void order() {
        std::vector<std::vector<int>> deps = pass_dependencies(idx_), users(np_);
        std::vector<int> pending(np_, 0);
        for (size_t i = 0; i < np_; ++i) {
            if (!keep_[i]) continue;
            for (int d : deps[i])
                if (keep_[d]) users[d].push_back(int(i)), ++pending[i];
        }
        std::priority_queue<int, std::vector<int>, std::greater<int>> ready;
        for (size_t i = 0; i < np_; ++i)
            if (keep_[i] && !pending[i]) ready.push(int(i));
        position_.assign(np_, -1);
        while (!ready.empty()) {
            int p = ready.top();
            ready.pop();
            position_[p] = int(order_.size());
            order_.push_back(p);
            for (int u : users[p])
                if (--pending[u] == 0) ready.push(u);
        }
    }

    // Lifetimes over the order: writer to last reader; history and persistent resources live
    // the whole frame; outputs until the end (presented/captured after the last pass).
    void lifetimes() {
        const int last = int(order_.size()) - 1;
        first_.assign(idx_.resources.size(), -1);
        last_.assign(idx_.resources.size(), -1);
        auto use = [&](int r, int at) {
            first_[r] = first_[r] < 0 ? at : std::min(first_[r], at);
            last_[r] = std::max(last_[r], at);
        };
        for (int p : order_) {
            for (const auto& b : inputs_[p]) use(b.resource, position_[p]);
            for (const auto& b : idx_.outputs[p]) use(b.resource, position_[p]);
        }
        captured_ = {output_res_.begin(), output_res_.end()};
        for (size_t r = 0; r < idx_.resources.size(); ++r) {
            if (captured_.count(int(r)) && first_[r] < 0) use(int(r), 0);  // a persistent output nobody writes
            if (first_[r] < 0) continue;
            if (idx_.resources[r].history || idx_.resources[r].persistent) first_[r] = 0, last_[r] = last;
            if (captured_.count(int(r))) last_[r] = last;
        }
    }

    // Resolved parameters: defaults + graph + variables + --set (buffers may be sized by them).
    void resolve_params() {
        params_.assign(np_, json());
        for (int p : order_) {
            params_[p] = idx_.types[p]->default_params();
            for (const auto& [k, v] : g_.passes[p].params.items())
                resolve_param(g_, *idx_.types[p]->param(k), v, params_[p][k]);
        }
    }

    CompiledGraph header() const {
        CompiledGraph cg;
        cg.file = g_.path;
        cg.name = g_.name;
        cg.output_size = output_size_;
        cg.dirs = g_.dirs;
        cg.instance_types = idx_.instance_types;
        for (const auto& v : g_.variables) cg.variables[v.name] = v.value;
        cg.culled = culled_;
        return cg;
    }

    // Compiled resources: the used ones, ordered by first use (then declaration), with their
    // formats, sizes and bytes.
    void resolve_resources(CompiledGraph& cg) {
        std::vector<int> used;
        for (size_t r = 0; r < idx_.resources.size(); ++r)
            if (first_[r] >= 0) used.push_back(int(r));
        std::stable_sort(used.begin(), used.end(), [&](int a, int b) { return first_[a] < first_[b]; });
        compiled_index_.assign(idx_.resources.size(), -1);
        for (int r : used) {
            compiled_index_[r] = int(cg.resources.size());
            cg.resources.push_back(resource(r));
        }
    }

    CompiledResource resource(int r) const {
        const ResourceDecl& d = idx_.resources[r];
        const PinDecl* pin = idx_.writer_pin(r);
        CompiledResource c;
        c.name = d.name;
        c.kind = d.kind;
        c.history = d.history;
        c.persistent = d.persistent;
        c.captured = captured_.count(r) > 0;
        c.first_use = first_[r];
        c.last_use = last_[r];
        if (d.kind == PinKind::Texture) {
            c.format = idx_.resolved_format(r);
            const FormatInfo* f = find_format(c.format);
            glm::ivec2 size;
            resolve_size(idx_, r, output_size_, size);  // validated above
            c.width = size.x;
            c.height = size.y;
            c.mips = d.mips >= 0 ? d.mips : pin ? pin->mips : 1;
            if (c.mips == 0) c.mips = full_mip_count(c.width, c.height);
            c.mips = std::min(c.mips, full_mip_count(c.width, c.height));
            c.internal_format = f ? f->internal_format : 0;
            c.bytes = f ? texture_bytes(*f, c.width, c.height, c.mips) : 0;
        } else {
            const size_t pixels = size_t(output_size_.x) * size_t(output_size_.y);
            if (d.bytes) c.bytes = d.bytes;
            else if (d.bytes_per_pixel) c.bytes = d.bytes_per_pixel * pixels;
            else if (pin && pin->bytes_from_params && !params_[idx_.writer(r)].is_null())
                c.bytes = pin->bytes_from_params(params_[idx_.writer(r)]);
            else if (pin && pin->bytes) c.bytes = pin->bytes;
            else if (pin) c.bytes = pin->bytes_per_pixel * pixels;
            c.width = c.height = 0;
        }
        return c;
    }

    // Passes in execution order, with resolved parameters and bindings; the outputs by name.
    void compiled_passes(CompiledGraph& cg) const {
        for (int p : order_) {
            const PassDecl& d = g_.passes[p];
            CompiledPass c;
            c.name = d.name;
            c.type = idx_.types[p];
            c.pointer = d.pointer;
            c.params = params_[p];
            c.hooks = d.hooks;
            c.shaders = pass_shaders(*c.type, g_.dirs, c.hooks);
            for (const auto& b : inputs_[p]) c.bindings[b.pin] = {compiled_index_[b.resource], b.prev};
            for (const auto& b : idx_.outputs[p]) {
                c.bindings[b.pin] = {compiled_index_[b.resource], false};
                cg.resources[compiled_index_[b.resource]].writer = int(cg.passes.size());
            }
            cg.passes.push_back(std::move(c));
        }
        for (size_t i = 0; i < g_.outputs.size(); ++i) {
            OutputDecl o = g_.outputs[i];
            o.resource = idx_.resources[output_res_[i]].name;
            cg.outputs.push_back(o);
        }
    }

    const GraphFile& g_;
    const size_t np_;
    const glm::ivec2 output_size_;
    const GraphIndex idx_;
    std::vector<char> enabled_, keep_;                  // per pass
    std::vector<std::vector<BoundPin>> inputs_;         // per pass: without disabled writers' reads
    std::vector<int> output_res_;                       // per graph output: its resource
    std::set<int> captured_;
    std::vector<CulledPass> culled_;
    std::vector<int> order_, position_;                 // passes to run; a pass's place in order_
    std::vector<int> first_, last_, compiled_index_;    // per resource
    std::vector<json> params_;                          // per pass
};

}  // namespace

CompiledGraph compile_graph(const GraphFile& g, const PassRegistry& reg, glm::ivec2 output_size, float pixel_scale) {
    std::optional<GraphFile> resolved;
    CompiledGraph cg = Compilation(with_hooks_resolved(g, reg, resolved), reg, output_size).run();
    cg.pixel_scale = pixel_scale;
    return cg;
}

}  // namespace pathlet
