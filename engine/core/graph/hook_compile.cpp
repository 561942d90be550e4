#include "hook_compile.hpp"

#include "graph_internal.hpp"
#include "hook_params.hpp"
#include "pass_bindings.hpp"

#include <pathlet/lines.hpp>
#include <pathlet/shader.hpp>

#include <set>

namespace pathlet {

using namespace graph_detail;

std::vector<Diagnostic> compile_hooks(const GraphFile& file, const PassRegistry& reg) {
    std::optional<GraphFile> resolved;
    const GraphFile& g = with_hooks_resolved(file, reg, resolved);
    std::vector<Diagnostic> out;
    std::set<std::pair<std::string, HookRole>> done;
    for (const PassDecl& p : g.passes) {
        const PassTypeInfo* t = reg.find(p.type);
        if (!t) continue;  // validate_graph names it
        for (const HookBinding& h : p.hooks) {
            if (!done.insert({h.file, h.role}).second) continue;
            // As the pass's programs see it: the shader path, the pass's binding defines.
            const ShaderSource source = pass_shaders(*t, g.dirs, {});
            std::vector<std::string> defines = PassBindings(*t).defines();
            if (*hook_role(h.role).defines) defines.push_back(hook_role(h.role).defines);
            try {
                ShaderProgram::build({lines::hook_stage(source, h.role, h.file)}, source, defines);
            } catch (const ShaderError& e) {
                // Alone, a hook has no main(): the link fails once the stage has compiled.
                if (std::string(e.what()).rfind("GLSL link error", 0) == 0) continue;
                const std::string at =
                    p.params.contains(h.param) ? p.pointer + "/params/" + pointer_escape(h.param) : p.pointer + "/type";
                out.push_back({g.path, at, h.param + " " + h.file + " does not compile: " + e.what()});
            }
        }
    }
    return out;
}

}  // namespace pathlet
