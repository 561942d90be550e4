// Hook files as parameters: a line pass's `color_hook` and `width_hook` parameters name GLSL
// files, and the uniforms those files annotate with @param become parameters of that pass
// instance, declared once, in the shader:
//
//   uniform float u_start;  // @param 0.3 [0, 1] "age where the fade begins"
//
// validated, settable with --set pass.start=..., shown by `passes --describe` and the viewer,
// and bound to u_start by declaration. The grammar (engine/lines/shaders/line_hooks.glsl):
//
//   uniform float|int u_<name>;  // @param DEFAULT [MIN, MAX] [px] "doc"
//   uniform bool u_<name>;       // @param true|false "doc"
//   uniform int u_<name>;        // @param CHOICE {CHOICE, CHOICE, ...} "doc"   (enum: the index)
//   uniform vec3 u_<name>;       // @param [X, Y, Z] "doc"   or   @param color #rrggbb|[R, G, B] "doc"
//
// `px` marks a length in pixels (scaled with --ssaa). Files the hook #includes count too.
// Pure text: no GL, so `pathlet validate` and the graph tests need no context.
#pragma once

#include <pathlet/pass.hpp>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlet {

// A hook file or @param line that cannot be used: "<file>:<line>: <message>".
struct HookError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Where a pass type's shaders are found, in order: PATHLET_SHADER_PATH, the plugin's own
// shader folder, the shared shaders; then `graph_dirs` (the graph file's folder and those of
// the graphs it extends: hook files next to the graph; and hook files the user named by path,
// GraphFile::dirs).
std::vector<std::string> shader_search_path(const PassTypeInfo& type, const std::vector<std::string>& graph_dirs);

// Where a pass's hook files are found, in order: `graph_dirs` first (a hook next to the graph
// wins over a shipped file of the same name: the graph's folder is one the user chose), then
// the shader path. Scanning for @param, `graph --plan` and the programs all find hooks here.
std::vector<std::string> hook_search_path(const PassTypeInfo& type, const std::vector<std::string>& graph_dirs);
// The file hook `name` (a hook parameter's value) is, on hook_search_path. Throws HookError.
std::string find_hook_file(const std::string& name, const PassTypeInfo& type, const std::vector<std::string>& graph_dirs);

// A hook name as a graph may give it: a plain file name ending in .frag, .geom or .glsl, found
// on the shader path (no folders, no '..'), or an absolute path that is itself an entry of
// `graph_dirs` (a file the user named: --set, Python). Returns "" or what is wrong with it.
std::string check_hook_name(const std::string& name, const std::vector<std::string>& graph_dirs = {});

// The parameters a hook file (and what it includes) declares with @param. `role` is "color"
// or "width": the file must define that hook's function. Throws HookError naming file and line.
std::vector<ParamDecl> hook_params(const std::string& name, const std::string& role,
                                   const std::vector<std::string>& dirs);

// The type of one pass instance: `type` plus the parameters of the hooks `params` names
// (values of the type's hook parameters; absent ones take their defaults). The type itself
// when its hooks declare nothing. Throws HookError.
std::shared_ptr<const PassTypeInfo> instance_type(const PassTypeInfo& type, const json& params,
                                                  const std::vector<std::string>& graph_dirs);

}  // namespace pathlet
