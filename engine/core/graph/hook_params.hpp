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

#include "graph_model.hpp"

#include <pathlet/pass.hpp>

#include <map>
#include <memory>
#include <set>
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
// the graphs it extends).
std::vector<std::string> shader_search_path(const PassTypeInfo& type, const std::vector<std::string>& graph_dirs);

// Where a pass's programs find their files: shader_search_path, and its resolved hook files.
ShaderSource pass_shaders(const PassTypeInfo& type, const std::vector<std::string>& graph_dirs,
                          const std::vector<HookBinding>& hooks);

// A hook name as a graph may give it: a plain file name ending in .frag, .geom or .glsl, found
// next to the graph or on the shader path (no folders, no '..'), or an absolute path that is one
// of `user_files` (a file the user named: --set, Python). Returns "" or what is wrong with it.
std::string check_hook_name(const std::string& name, const std::set<std::string>& user_files = {});

// A hook resolved: `name` (as the graph gives it) found — a file of the user's by its path,
// else next to the graph first (a folder the user chose wins over a shipped file of the same
// name), then on the type's shader path — and read once for the parameters it (and what it
// includes) declares with @param. The file must define the role's function. Throws HookError
// naming the file and line.
HookBinding bind_hook(const PassTypeInfo& type, HookRole role, const std::string& name,
                      const std::vector<std::string>& graph_dirs, const std::set<std::string>& user_files = {});

// The type of one pass instance: `type` plus the parameters its hooks declare (the type itself
// when they declare none). Throws HookError for a parameter that clashes with the type's or is
// declared by both hooks differently.
std::shared_ptr<const PassTypeInfo> instance_type(const PassTypeInfo& type, const std::vector<HookBinding>& hooks);

// The type with its hooks bound: the names given by role, the type's defaults for the others
// (no graph: the shader path only). For `passes --describe`. Throws HookError.
std::shared_ptr<const PassTypeInfo> instance_type_with(const PassTypeInfo& type,
                                                       const std::map<HookRole, std::string>& names = {},
                                                       const std::set<std::string>& user_files = {});

}  // namespace pathlet
