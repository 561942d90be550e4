#include "runtime.hpp"

#include <cstdio>

namespace pathlet {

void Runtime::load_plugins(const std::vector<std::string>& extra_dirs) {
    host.load_dirs(PluginHost::search_path(extra_dirs));
}

GlContext& Runtime::ensure_gl(bool quiet) {
    if (!gl) {
        gl = GlContext::create_headless();
        if (!quiet) std::fprintf(stderr, "%s\n", gl->summary().c_str());
    }
    return *gl;
}

std::string Runtime::plugin_problems_note() const {
    if (host.problems().empty()) return "";
    std::string s = "\nnote: " + std::to_string(host.problems().size()) + " plugin(s) failed to load:";
    for (const auto& p : host.problems()) s += "\n  " + p;
    return s;
}

}  // namespace pathlet
