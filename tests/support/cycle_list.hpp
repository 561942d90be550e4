// A test pass that corrupts variant 2's lists in one frame, to see a cut walk reported: between
// fill_list and the resolve it copies the heads on (its output `heads_out`, which the resolve
// reads instead) and, in the frame whose index is its parameter `frame`, links node 0 to
// itself, so the list holding node 0 is cyclic. cyclic_list_graph() writes a graph that puts it
// into variant2_exact.
#pragma once

#include "runtime.hpp"

#include <string>

namespace pathlet {

// Adds the pass type "test_cycle_list" to the runtime's registry (once).
void add_cycle_list_pass(Runtime& rt);
// Writes `path`: variant2_exact with the list made cyclic in frame `frame` (executor frame
// index: warm-up frames count); returns `path`.
std::string write_cyclic_list_graph(const std::string& path, int frame);

}  // namespace pathlet
