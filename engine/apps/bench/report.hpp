// The files a bench run leaves: results.json (its layout: results.hpp), frames.csv (one row per frame and pass), summary.csv (median/p5/p95 per pass),
// passes.svg (stacked per-pass bars) and, with a sweep, sweep.svg (frame time against the value).
// Everything is rebuilt from the JSON, so shard merges write exactly what one run would.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace pathlet::cli::bench {

// The table a person reads: per run and pass, median/p5/p95 ms.
std::string summary_csv(const nlohmann::json& report);
std::string frames_csv(const nlohmann::json& report);

// Writes the files above into dir (atomically, each); returns their names.
std::vector<std::string> write_report_dir(const std::string& dir, const nlohmann::json& report);

}  // namespace pathlet::cli::bench
