// How a command reports a graph that cannot be run: every diagnostic (FILE:/json/pointer:
// message), then the plugins that failed to load (often the cause of an unknown pass type).
#pragma once

#include "graph/graph_model.hpp"
#include "runtime.hpp"

#include <cstdio>

namespace pathlet::cli {

// What resolving a graph did that its author may not expect (GraphFile::notes), on stderr.
inline void print_graph_notes(const GraphFile& g) {
    for (const auto& n : g.notes) std::fprintf(stderr, "note: %s\n", n.c_str());
}

// Prints the report to stderr; returns 1, the exit status of failed work.
inline int report_graph_error(const GraphError& e, const Runtime& rt) {
    for (const auto& d : e.diagnostics) std::fprintf(stderr, "%s\n", d.str().c_str());
    std::fprintf(stderr, "%s", rt.plugin_problems_note().c_str());
    return 1;
}

}  // namespace pathlet::cli
