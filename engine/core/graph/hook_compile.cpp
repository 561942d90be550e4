#include "hook_compile.hpp"

#include "graph_internal.hpp"
#include "hook_params.hpp"

#include <pathlet/lines.hpp>
#include <pathlet/shader.hpp>

#include <filesystem>
#include <set>

namespace pathlet {

using namespace graph_detail;

std::vector<Diagnostic> compile_hooks(const GraphFile& g, const PassRegistry& reg) {
    std::vector<Diagnostic> out;
    std::set<std::pair<std::string, std::string>> done;  // (file, role)
    for (const PassDecl& p : g.passes) {
        const PassTypeInfo* t = reg.find(p.type);
        if (!t) continue;  // validate_graph names it
        std::vector<std::string> defines;  // as the executor gives them: buffer pins in declaration order
        for (const PinDecl& pin : t->pins)
            if (pin.kind == PinKind::Buffer) defines.push_back(binding_define(pin.name) + " " + std::to_string(defines.size()));
        for (const ParamDecl& d : t->params) {
            if (d.hook.empty()) continue;
            json value = d.def;
            if (p.params.contains(d.name) && !resolve_param(g, d, p.params[d.name], value).empty()) continue;
            if (!value.is_string() || value.get<std::string>().empty()) continue;  // the kit's default
            std::string file;
            try {
                file = std::filesystem::absolute(find_hook_file(value.get<std::string>(), *t, g.dirs)).lexically_normal();
            } catch (const HookError&) {
                continue;  // validate_graph names a missing hook
            }
            if (!done.insert({file, d.hook}).second) continue;
            std::vector<std::string> dirs = hook_search_path(*t, g.dirs);
            dirs.push_back(file);  // found by its path, as the executor finds it
            std::vector<std::string> defs = defines;
            if (d.hook == "width") defs.push_back("LINE_WIDTH_HOOKED");
            try {
                ShaderProgram::from_files({lines::hook_entry(file, d.hook)}, dirs, defs);
            } catch (const ShaderError& e) {
                // Alone, a hook has no main(): the link fails once the stage has compiled.
                if (std::string(e.what()).rfind("GLSL link error", 0) == 0) continue;
                const std::string at = p.params.contains(d.name) ? p.pointer + "/params/" + pointer_escape(d.name)
                                                                 : p.pointer + "/type";
                out.push_back({g.path, at, d.name + " " + file + " does not compile: " + e.what()});
            }
        }
    }
    return out;
}

}  // namespace pathlet
