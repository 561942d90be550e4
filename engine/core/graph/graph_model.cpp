#include "graph_model.hpp"

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

}  // namespace pathlet
