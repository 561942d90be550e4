// The files a bench run leaves: results.json (header + every run with every frame),
// frames.csv (one row per frame and pass), summary.csv (median/p5/p95 per pass),
// passes.svg (stacked per-pass bars) and, with a sweep, sweep.svg (frame time against the value).
// Everything is rebuilt from the JSON, so shard merges write exactly what one run would.
#pragma once

#include "profiler/profiler.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace pathlet::cli::bench {

// A run's entry: profiler summary (meta, timing, frame, passes) plus "frames" (every frame).
nlohmann::json run_entry(const Profiler& p, const nlohmann::json& meta);

// The table a person reads: per run and pass, median/p5/p95 ms.
std::string summary_csv(const nlohmann::json& report);
std::string frames_csv(const nlohmann::json& report);

// Writes the files above into dir (atomically, each); returns their names.
std::vector<std::string> write_report_dir(const std::string& dir, const nlohmann::json& report);

// Machine description for the header: host, CPU model, cores.
nlohmann::json machine_info();
// FNV-1a 64 of a file's bytes as 16 hex digits ("" when unreadable).
std::string file_hash(const std::string& path);

}  // namespace pathlet::cli::bench
