// `pathlet bench --plots`: the Matplotlib figures (PNG, PDF) of a results folder, drawn by
// `python3 -m pathlet.plot` (engine/apps/python/pathlet/plot.py) so there is one plotting code.
#pragma once

#include <string>

namespace pathlet::cli::bench {

// Runs the interpreter the module was built for (else python3 on PATH) on dir/results.json,
// with the build tree's package first on PYTHONPATH when the command runs from the build
// tree. Returns "" on success, else what went wrong (the plot script's own errors go to stderr).
std::string write_matplotlib_plots(const std::string& dir);

}  // namespace pathlet::cli::bench
