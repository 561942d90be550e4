// The shipped graphs (graphs/*.json of the source tree) for tests that run every one of them:
// a graph added later is tested without touching the tests.
#pragma once

#include "graph/graph_model.hpp"

#include <string>
#include <vector>

namespace pathlet {

struct ShippedGraph {
    std::string name;  // file stem, e.g. "variant1_lineao"
    std::string path;
    GraphFile file;
    bool draws_lines = false;  // has a pass of the line kit's types (demo_blur draws no data)
    bool has_variable(const std::string& v) const;
    bool has_pass(const std::string& pass_name) const;
    std::string variable_default(const std::string& v) const;  // JSON text, "" when absent
    // Why this graph cannot run on the current GL context ("" when it can): a pass that needs an
    // extension the driver lacks (mlab_blend: GL_ARB_fragment_shader_interlock, which llvmpipe
    // has not). Tests that render every graph skip it, saying so; passes/mlab_blend/tests checks
    // its setup error. Needs a current context.
    std::string unsupported_here() const;
};

// Sorted by name; read once per process.
const std::vector<ShippedGraph>& shipped_graphs();
const ShippedGraph& shipped_graph(const std::string& name);  // throws std::out_of_range
std::vector<std::string> shipped_graph_names(bool only_drawing_lines);

}  // namespace pathlet
