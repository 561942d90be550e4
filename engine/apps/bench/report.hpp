// The files a bench run leaves: results.json (its layout: results.hpp), frames.csv (one row per frame and pass), summary.csv (median/p5/p95 per pass),
// passes.svg (stacked per-pass bars) and, with a sweep, sweep.svg (frame time against the value).
// Everything is rebuilt from the JSON, so shard merges write exactly what one run would.
#pragma once

#include "profiler/profiler.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace pathlet::cli::bench {

// The table a person reads: per run and pass, median/p5/p95 ms.
std::string summary_csv(const nlohmann::json& report);
std::string frames_csv(const nlohmann::json& report);

// One row of the summary printed at the end of a bench: a run's frame times, its wall-clock
// frame rate and what its line passes culled ("-" where none).
struct SummaryRow {
    std::string label;
    Profiler::Stats frame;
    double wall_fps = 0;
    std::string chunks = "-";
    bool gpu_timing = true;  // GL timestamps (a GPU); false: glFinish-bracketed clocks (llvmpipe)
};
// The summary: median/p5/p95 frame ms, fps of the median frame ("frame fps", as the timing
// table's "fps (median frame)"), wall fps ("fps (wall clock)"), chunks. On a GPU a run whose
// p95/p5 exceeds Profiler::kUnstableRatio is marked UNSTABLE (its clock changed during the run),
// with a line saying what that means; llvmpipe has no clock governor, so nothing is marked there.
std::string summary_table(const std::vector<SummaryRow>& rows);

// Writes the files above into dir (atomically, each); returns their names.
std::vector<std::string> write_report_dir(const std::string& dir, const nlohmann::json& report);

}  // namespace pathlet::cli::bench
