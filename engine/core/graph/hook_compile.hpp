// `pathlet validate` compiles every hook a graph reaches: each hook file of each pass, alone, as
// the stage its role needs after the line kit's definitions (lines::hook_stage), with the pass's
// buffer-pin defines. A compile error names the hook's file and line (ShaderProgram maps them).
// Needs a current GL context (the headless one: the driver's own compiler, nothing emulated).
#pragma once

#include "graph_model.hpp"

#include <vector>

namespace pathlet {

// One diagnostic per hook file that does not compile (each file and role once), at the
// parameter that names it (or the pass's type, for its default hook).
std::vector<Diagnostic> compile_hooks(const GraphFile& g, const PassRegistry& reg);

}  // namespace pathlet
