#include "graph_model.hpp"

#include <pathlet/text.hpp>

namespace pathlet {

namespace {
std::string all_messages(const std::vector<Diagnostic>& d) {
    std::string s;
    for (size_t i = 0; i < d.size(); ++i) s += (i ? "\n" : "") + d[i].str();
    return s.empty() ? "graph error" : s;
}
}  // namespace

GraphError::GraphError(std::vector<Diagnostic> d) : std::runtime_error(all_messages(d)), diagnostics(std::move(d)) {}

int CompiledGraph::find_resource(const std::string& n) const {
    for (size_t i = 0; i < resources.size(); ++i)
        if (resources[i].name == n) return int(i);
    return -1;
}

int CompiledGraph::resolve(const std::string& name, std::string* why) const {
    if (const int r = find_resource(name); r >= 0) return r;
    if (const size_t dot = name.find('.'); dot != std::string::npos)
        for (const auto& p : passes)
            if (p.name == name.substr(0, dot))
                if (const auto b = p.bindings.find(name.substr(dot + 1)); b != p.bindings.end() && b->second.resource >= 0)
                    return b->second.resource;
    if (why) {
        std::vector<std::string> known;
        for (const auto& r : resources) known.push_back(r.name);
        *why = "no resource '" + name + "' in the compiled graph" + text::did_you_mean(name, known) +
               "; its resources: " + text::join(known);
        for (const auto& c : culled) *why += "; pass '" + c.name + "' is culled (" + c.reason + ")";
    }
    return -1;
}

}  // namespace pathlet
