// bench --compare: per graph, size and pass, the change against a baseline report, with a
// verdict that ignores noise: a change counts only when the p5..p95 ranges do not overlap AND
// the medians differ by more than the threshold. Both conditions, because on a shared 2-core
// machine either alone flags plain re-runs.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace pathlet::cli::bench {

struct CompareResult {
    std::string table;  // printable
    int regressions = 0, improvements = 0, compared = 0;
    std::vector<std::string> missing;  // in the baseline, not in the current results
};

// `baseline` and `current`: bench reports (an object with "runs", or the older plain array).
// threshold: relative, 0.5 = 50 % slower.
CompareResult compare_reports(const nlohmann::json& baseline, const nlohmann::json& current, double threshold);

}  // namespace pathlet::cli::bench
