// Graph files (what the JSON says) and compiled graphs (what runs). Pure data, no GL calls:
// the compiler works without a context, so `pathlet validate/graph` and the tests need none.
#pragma once

#include <pathlet/pass.hpp>
#include <pathlet/shader_source.hpp>

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlet {

class PassRegistry;

// One problem in a graph file: "<file>:<json pointer>: <message>".
struct Diagnostic {
    std::string file;
    std::string pointer;  // JSON pointer, e.g. "/passes/2/params/radius"
    std::string message;
    int line = 0, column = 0;  // set for JSON syntax errors (there is no pointer then)
    std::string str() const {
        if (line > 0) return file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message;
        return file + ":" + (pointer.empty() ? "/" : pointer) + ": " + message;
    }
};

// Thrown when a graph has errors; holds every one of them (validation never stops at the first).
struct GraphError : std::runtime_error {
    std::vector<Diagnostic> diagnostics;
    explicit GraphError(std::vector<Diagnostic> d);
};

// ---- as written -------------------------------------------------------------------------

struct VariableDecl {
    std::string name;
    ParamDecl decl;   // type, default, range, doc (same rules as pass parameters)
    json value;       // default or --set override, already coerced; null: its declaration is wrong
    std::string pointer;
    std::string set_by;  // the --set that gave `value`, "" when the graph did
};

// A hook of a pass, resolved once when the graph loads (resolve_hooks): the file the graph
// names, where it was found and the parameters it declares with @param.
struct HookBinding {
    HookRole role = HookRole::color;
    std::string param;              // "color_hook"
    std::string name;               // as the graph or --set gives it: "my_fade.glsl", or a path of the user's
    std::string file;               // found: absolute, normalised
    std::vector<ParamDecl> params;  // what it declares (@param), with their defaults
};

struct SizeDecl {
    std::string relative_to = "output";  // "output" or a resource name; "" when absolute
    float scale_x = 1.0f, scale_y = 1.0f;
    int width = 0, height = 0;           // absolute size when relative_to == ""
};

struct ResourceDecl {
    std::string name;
    PinKind kind = PinKind::Texture;
    std::string format;       // "" = from the writing pin
    std::optional<SizeDecl> size;  // unset = from the writing pin (scale x output)
    int mips = -1;            // -1 = from the pin; 0 = full chain
    size_t bytes = 0, bytes_per_pixel = 0;  // buffers; 0 = from the pin
    bool history = false;     // keeps last frame's content, readable as "<name>@prev"
    bool persistent = false;  // never pooled; content survives across frames
    bool implicit = false;    // made for an unbound output pin ("<pass>.<pin>")
    bool internal = false;    // ... for a pass's internal texture: nobody else reads it
    std::string pointer;
};

struct PassDecl {
    std::string name;
    std::string type;
    json params = json::object();                // as written; values may be "$variable"
    std::map<std::string, std::string> inputs;   // pin -> "resource", "pass.pin" or "resource@prev"
    std::map<std::string, std::string> outputs;  // pin -> "resource"
    json enabled = true;                         // bool or "$variable"
    std::string pointer;
    // When each parameter was last written: a layer number, counting the graph files of the
    // `extends` chain from the deepest base (0) and then each --set. A hook's parameter written
    // before the hook was last replaced was set for the replaced hook (resolve_hooks).
    std::map<std::string, int> written;
    // Each time a graph or a --set replaced one of the pass's hooks.
    struct HookSwap {
        std::string param;          // "color_hook"
        int layer = 0;
        std::string by;             // the extending graph file, or "--set ..."
        std::string before, after;  // hook names ("" = the type's default)
    };
    std::vector<HookSwap> swaps;
    // Resolved once (resolve_hooks): the pass's hooks and its type with their parameters
    // (null until then, and for a type the registry lacks).
    std::vector<HookBinding> hooks;
    std::shared_ptr<const PassTypeInfo> instance_type;
};

struct OutputDecl {
    std::string resource;     // "resource" or "pass.pin"
    std::string capture;      // path pattern, e.g. "out/{graph}/{frame:05}.png"; "" = none
    std::string pointer;
};

struct GraphFile {
    std::string path;
    int version = 1;
    // "name" of the file itself (never a base's), else the file's name without .json.
    std::string name, description;
    std::vector<VariableDecl> variables;
    std::vector<ResourceDecl> resources;
    std::vector<PassDecl> passes;
    std::vector<OutputDecl> outputs;
    std::vector<std::string> plugin_dirs;  // "plugin_dirs": folders of plugins, resolved against the file's folder
    // The file's folder and those of the graphs it extends: hook files next to a graph are
    // found there (before the shader path).
    std::vector<std::string> dirs;
    // Hook files the user named by path (--set, Python: Runtime::user_sets): the only paths a
    // hook may be; a graph file names hooks by file name.
    std::set<std::string> user_files;
    // What resolving the graph did that its author may not expect (a replaced hook's
    // parameters dropped), for the command to print as notes.
    std::vector<std::string> notes;
    // resolve_hooks ran: every pass's hooks and instance type are known. The problems it found
    // (a hook file missing, a bad @param line) are reported by validation, at their place.
    bool hooks_resolved = false;
    std::vector<Diagnostic> hook_problems;
    int layers = 1;  // layers of the extends chain and --set so far (PassDecl::written)
    std::vector<std::string> extends;      // the chain of base graphs, nearest first (file paths)
    // Folders of plugin_dirs whose plugins were not loaded because the folder is not trusted
    // (Runtime::load_graph_plugins, validate): "unknown pass type" says so instead of guessing a typo.
    struct UntrustedDir {
        std::string dir;                 // canonical
        std::vector<std::string> files;  // its plugin files, never opened
    };
    std::vector<UntrustedDir> untrusted_plugin_dirs;
};

// ---- compiled ---------------------------------------------------------------------------

struct CompiledResource {
    std::string name;
    PinKind kind = PinKind::Texture;
    std::string format;        // resolved format name
    GLenum internal_format = 0;
    int width = 0, height = 0, mips = 1;
    size_t bytes = 0;          // buffers: size; textures: memory estimate (all mips)
    bool history = false, persistent = false, captured = false;
    bool transient() const { return !history && !persistent && !captured; }
    int writer = -1;           // index into CompiledGraph::passes
    int first_use = -1, last_use = -1;  // pass indices in execution order
    int slot = -1;             // index into CompiledGraph::slots (pooled physical object)
};

struct Binding {
    int resource = -1;
    bool previous = false;     // reads last frame's content of a history resource
};

struct CompiledPass {
    std::string name;
    // The pass's type: the registry's, or its own copy with the parameters its hook files
    // declare (kept alive by CompiledGraph::instance_types).
    const PassTypeInfo* type = nullptr;
    json params;                                 // resolved: defaults + graph + variables + --set
    // Its hooks, as the graph resolved them (`graph --plan` names them), and where its programs
    // find their files: its type's shader path with the graph's folders, and those hook files.
    std::vector<HookBinding> hooks;
    ShaderSource shaders;
    std::map<std::string, Binding> bindings;     // pin -> resource
    std::string pointer;
};

// A physical GL object shared by resources whose lifetimes do not overlap.
struct PoolSlot {
    PinKind kind = PinKind::Texture;
    GLenum internal_format = 0;
    int width = 0, height = 0, mips = 1;
    size_t bytes = 0;
    std::vector<int> resources;
};

struct CulledPass {
    std::string name, reason;
};

struct CompiledGraph {
    std::string file, name;
    glm::ivec2 output_size{0};
    // Pixels of this render per pixel of the picture (render --ssaa N renders N x N larger and
    // downsamples): passes scale their pixel-measured parameters by it.
    float pixel_scale = 1.0f;
    std::vector<CompiledPass> passes;        // execution order (enabled, not culled)
    std::vector<CompiledResource> resources;
    std::vector<PoolSlot> slots;
    std::vector<CulledPass> culled;          // with the reason, for the log and --plan
    std::vector<OutputDecl> outputs;         // resource resolved to a name in `resources`
    size_t memory_unpooled = 0, memory_pooled = 0;
    json variables = json::object();         // resolved values, for reports
    std::vector<std::string> dirs;           // GraphFile::dirs: where hook files next to the graph are
    std::vector<std::shared_ptr<const PassTypeInfo>> instance_types;

    int find_resource(const std::string& name) const;
    // What a caller's name means: a resource, or PASS.PIN (the resource bound to that pin of a
    // pass that runs). -1 with `why` saying what there is (a did-you-mean, the culled passes).
    int resolve(const std::string& name, std::string* why = nullptr) const;
};

// Keeps resources out of the pool for the whole frame (their content is still theirs after the
// frame: a caller reads them back) and pools the rest again. std::invalid_argument naming a
// resource the graph lacks.
void keep_resources(CompiledGraph& cg, const std::vector<std::string>& names);

// ---- finding graphs -------------------------------------------------------------------

// A graph argument that is neither a file nor a shipped graph's name. The message is one line:
// what was given, the closest names (did-you-mean) and the shipped graphs.
struct GraphNotFound : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};
// The names of the shipped graphs (graphs/*.json in the share folder, without .json), sorted.
std::vector<std::string> shipped_graph_names();
// A graph argument as every command and list takes it: a file (path as given), or the name of a
// shipped graph (with or without .json). Throws GraphNotFound before anything else is done.
std::string find_graph_file(const std::string& arg);

// Why `name` cannot be a graph's name ("" when it can): it names the graph's folder in output
// paths ({graph}, quality --out, the output-folder record), so no '/', backslash, control
// characters, "." or "..". The parser applies it to "name" and to a file name standing in.
std::string graph_name_problem(const std::string& name);

// ---- the steps ------------------------------------------------------------------------

// Parses a graph file (comments allowed). Syntax and structure errors -> GraphError.
GraphFile parse_graph_file(const std::string& path);
// The same, collecting: the problems of its parts (a variable's default, a resource's format)
// go to `diags` and the rest is returned for validate_graph, so `validate` reports every error
// in one run (a variable declared wrongly has a null value). Unreadable JSON still throws.
GraphFile parse_graph_file(const std::string& path, std::vector<Diagnostic>& diags);
GraphFile parse_graph_json(const std::string& text, const std::string& path_for_messages);
// The JSON a graph file stands for: with the graphs it extends merged in (graph --expanded).
json expanded_graph_json(const std::string& path);

// Applies "--set name=value" / "--set pass.param=value" overrides, each a layer after the
// graph files', then resolves the hooks (resolve_hooks); problems go to `diags`. A hook may be
// an absolute path only when it is one of `user_files`, the hook files the user named on the
// command line or in Python (Runtime::user_sets).
void apply_overrides(GraphFile& g, const std::vector<std::string>& sets, const PassRegistry& reg,
                     std::vector<Diagnostic>& diags, const std::set<std::string>& user_files = {});

// Resolves every pass's hooks once: finds each hook file, reads its @param declarations, makes
// the pass's instance type, and drops the parameters set for a hook that a later graph or --set
// replaced (a note each in g.notes), with the graph variables that fed only them. Problems go
// to g.hook_problems. Does nothing the second time.
void resolve_hooks(GraphFile& g, const PassRegistry& reg);

// Every error at once: unknown pass type/param (did-you-mean), type/range errors, unconnected
// required inputs, kind/format mismatches, cycles, unknown resources, two writers of one resource.
std::vector<Diagnostic> validate_graph(const GraphFile& g, const PassRegistry& reg);

// Validates, culls (with reasons), orders topologically, resolves formats and sizes for the
// output size, computes lifetimes and pools transients. `pixel_scale`: render pixels per picture
// pixel (CompiledGraph::pixel_scale). Throws GraphError.
CompiledGraph compile_graph(const GraphFile& g, const PassRegistry& reg, glm::ivec2 output_size, float pixel_scale = 1.0f);

std::string graph_to_dot(const CompiledGraph& cg, const GraphFile& g);
std::string plan_to_text(const CompiledGraph& cg);   // order, lifetimes, memory before/after pooling
json plan_to_json(const CompiledGraph& cg);

}  // namespace pathlet
