#include "shipped_graphs.hpp"

#include <pathlet/gl.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace pathlet {

namespace {
// Pass types that draw the scene's lines through the line kit.
bool is_line_pass(const std::string& type) {
    for (const char* t : {"gbuffer", "isl", "geometric_fade", "fill_list", "fade_core", "wboit_accum", "mboit_moments",
                          "mboit_accum", "mlab_bucket", "mlab_blend"})
        if (type == t) return true;
    return false;
}
}  // namespace

bool ShippedGraph::has_variable(const std::string& v) const {
    return std::any_of(file.variables.begin(), file.variables.end(), [&](const VariableDecl& d) { return d.name == v; });
}

bool ShippedGraph::has_pass(const std::string& pass_name) const {
    return std::any_of(file.passes.begin(), file.passes.end(), [&](const PassDecl& p) { return p.name == pass_name; });
}

std::string ShippedGraph::unsupported_here() const {
    static const struct {
        const char* type;
        const char* extension;
    } needs[] = {{"mlab_blend", "GL_ARB_fragment_shader_interlock"}};
    for (const auto& n : needs) {
        if (std::none_of(file.passes.begin(), file.passes.end(), [&](const PassDecl& p) { return p.type == n.type; }))
            continue;
        GLint count = 0;
        glGetIntegerv(GL_NUM_EXTENSIONS, &count);
        bool found = false;
        for (GLint i = 0; i < count && !found; ++i)
            found = std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i))), n.extension) == 0;
        if (!found) return name + " needs " + n.extension + ", which this driver lacks (passes/mlab_blend/tests checks its error)";
    }
    return "";
}

std::string ShippedGraph::variable_default(const std::string& v) const {
    for (const auto& d : file.variables)
        if (d.name == v) return d.value.dump();
    return "";
}

const std::vector<ShippedGraph>& shipped_graphs() {
    static const std::vector<ShippedGraph> all = [] {
        std::vector<ShippedGraph> out;
        for (const auto& e : std::filesystem::directory_iterator(std::string(PATHLET_SOURCE_DIR) + "/graphs")) {
            if (e.path().extension() != ".json") continue;
            ShippedGraph g;
            g.name = e.path().stem().string();
            g.path = e.path().string();
            g.file = parse_graph_file(g.path);
            g.draws_lines = std::any_of(g.file.passes.begin(), g.file.passes.end(),
                                        [](const PassDecl& p) { return is_line_pass(p.type); });
            out.push_back(std::move(g));
        }
        std::sort(out.begin(), out.end(), [](const ShippedGraph& a, const ShippedGraph& b) { return a.name < b.name; });
        return out;
    }();
    return all;
}

const ShippedGraph& shipped_graph(const std::string& name) {
    for (const auto& g : shipped_graphs())
        if (g.name == name) return g;
    throw std::out_of_range("no shipped graph '" + name + "'");
}

std::vector<std::string> shipped_graph_names(bool only_drawing_lines) {
    std::vector<std::string> names;
    for (const auto& g : shipped_graphs())
        if (g.draws_lines || !only_drawing_lines) names.push_back(g.name);
    return names;
}

}  // namespace pathlet
