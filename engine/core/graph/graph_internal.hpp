// Helpers shared by the graph steps (parse, validate, compile, reports). Private to engine/core/graph.
#pragma once

#include "../formats.hpp"
#include <pathlet/text.hpp>
#include "../pass_registry.hpp"
#include "graph_model.hpp"
#include "util/text.hpp"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pathlet::graph_detail {

// ---- text (util/text.hpp) ----------------------------------------------------------------
using text::did_you_mean;
using text::join;
using text::pointer_escape;
using text::quoted;

// ---- references -------------------------------------------------------------------------
// "name@prev" -> {name, prev = true}
struct Ref {
    std::string name;
    bool prev = false;
};
Ref split_ref(const std::string& text);

// One pin of a pass bound to a resource, as resolved from the file.
struct BoundPin {
    std::string pin;
    const PinDecl* decl = nullptr;  // nullptr: unknown pin (already reported)
    int resource = -1;              // -1: unresolved (already reported)
    bool prev = false;
    std::string pointer;            // /passes/i/inputs/pin
};

// What the file's names refer to: pass types, declared + implicit resources, pin bindings and
// writers. Built once per validate/compile; resolution problems (unknown pass type, pin,
// resource, pass.pin) go to the diagnostics given to build_index.
struct GraphIndex {
    GraphIndex() = default;
    GraphIndex(const GraphIndex&) = delete;  // `writers` points into `outputs`
    GraphIndex(GraphIndex&&) = default;

    const GraphFile* g = nullptr;
    const PassRegistry* reg = nullptr;
    std::vector<const PassTypeInfo*> types;             // per pass (its instance type); nullptr when unknown
    std::vector<std::shared_ptr<const PassTypeInfo>> instance_types;  // keeps types with hook parameters alive
    std::vector<ResourceDecl> resources;                // declared, then implicit "<pass>.<pin>"
    std::map<std::string, int> resource_by_name;
    std::map<std::string, int> pass_by_name;            // first pass of that name
    std::vector<std::vector<BoundPin>> inputs, outputs; // per pass, in pin-name order
    std::vector<std::vector<std::pair<int, const BoundPin*>>> writers;  // per resource, file order

    int find_resource(const std::string& name) const;
    // "resource" or "pass.pin" -> resource index. -1 with `err` set, or -1 with `err` empty when
    // the problem lies elsewhere and was reported there (unknown pass type, bad output binding).
    // A pass's internal texture is no other pass's input, but a graph output may capture it
    // (allow_internal): an intermediate to look at.
    int resolve(const std::string& ref, std::string& err, bool allow_internal = false) const;
    int writer(int r) const { return writers[r].empty() ? -1 : writers[r][0].first; }
    const PinDecl* writer_pin(int r) const;
    std::string resolved_format(int r) const;  // the resource's format, else its writer pin's; "" unknown
    std::vector<std::string> resource_names() const;
};
GraphIndex build_index(const GraphFile& g, const PassRegistry& reg, std::vector<Diagnostic>& diags);

// Per pass: the passes whose outputs it reads this frame (writers of its non-@prev inputs,
// itself excluded), sorted, without duplicates.
std::vector<std::vector<int>> pass_dependencies(const GraphIndex& idx);

// The checks of validate_graph over a built index.
void validate_index(const GraphIndex& idx, std::vector<Diagnostic>& diags);
// Values that must agree: parameter ranges and what a pass shares with an input's writer
// (graph_agree.cpp).
void check_agreement(const GraphIndex& idx, std::vector<Diagnostic>& diags);

// `g` itself when its hooks are resolved, else a copy with them resolved in `copy` (a graph
// validated or compiled without apply_overrides).
const GraphFile& with_hooks_resolved(const GraphFile& g, const PassRegistry& reg, std::optional<GraphFile>& copy);

// ---- reading (graph_parse.cpp, graph_extends.cpp) -----------------------------------------
// A graph file's JSON (comments allowed, nesting and size capped), errors placed by line.
json graph_json_from_text(const std::string& text, const std::string& path);
json read_graph_json(const std::string& path);
// What each graph file of an extends chain wrote, by layer (0 = the deepest base): per pass
// the layer of each parameter's last write and the hooks each layer replaced (PassDecl).
struct LayerLog {
    int layers = 0;
    std::map<std::string, std::map<std::string, int>> written;  // pass -> param -> layer
    std::vector<std::pair<std::string, PassDecl::HookSwap>> swaps;  // pass, swap
};
// `root` (read from `path`) with its "extends" chain merged in; `dirs` gets the folders of the
// file and its bases, `chain` the base files, `log` what each file wrote.
json expand_extends(json root, const std::string& path, std::vector<std::string>& dirs, std::vector<std::string>& chain,
                    LayerLog* log = nullptr);
// The hook names the passes of a graph's JSON give (a "$variable" read from the variable's
// default; absent: "" for the type's default): pass -> hook parameter -> name.
std::map<std::string, std::map<std::string, std::string>> hook_names(const json& graph);

// ---- values -----------------------------------------------------------------------------
const VariableDecl* find_variable(const GraphFile& g, const std::string& name);
std::vector<std::string> variable_names(const GraphFile& g);
bool is_variable_ref(const json& v);  // "$name"
// A parameter value as written (literal or "$var") -> coerced value; returns an error or "".
std::string resolve_param(const GraphFile& g, const ParamDecl& d, const json& written, json& out);
// `enabled` (bool or "$var" naming a bool variable) -> bool; returns an error or "".
std::string resolve_enabled(const GraphFile& g, const json& enabled, bool& out);

// ---- sizes and memory -------------------------------------------------------------------
// Texture size of resource r for the given output size, following relative_to chains
// (rounding up, at least 1). Returns an error (unknown/cyclic/buffer base) or ""; `at` gets
// the resource whose size declaration holds the problem.
std::string resolve_size(const GraphIndex& idx, int r, glm::ivec2 output, glm::ivec2& out, int* at = nullptr);
int full_mip_count(int w, int h);
size_t texture_bytes(const FormatInfo& f, int w, int h, int mips);
// Memory the executor allocates for a resource: history keeps two copies.
size_t allocated_bytes(const CompiledResource& r);

// ---- pooling (graph_pool.cpp) -------------------------------------------------------------
// Assigns CompiledResource::slot and fills CompiledGraph::slots and the memory totals.
void assign_slots(CompiledGraph& cg);

}  // namespace pathlet::graph_detail
