// bench --compare: per graph, size and pass, the change against a baseline report, measured
// against the machine's own speed and with a verdict that ignores noise.
//
// Speed: each results.json records a fixed calibration workload timed before and after every
// run (bench/calibration.hpp). A run's times are also read on the baseline machine's speed
// (divided by the ratio of its calibration to the baseline run's), so a machine that is busy
// (or a slower one) does not read as a regression; the comparison says how much slower or
// faster the machine itself was. The calibration only excuses: a regression must show both as
// measured and on the machine's speed (a calibration that over-corrects cannot make one).
// Verdict: a change counts only when it is large (the medians differ by more than the
// threshold), clear over the per-frame samples (a one-sided Mann-Whitney rank test, p below
// kMaxP) and the middle halves of the samples (p5..p95 for reports without frames) lie apart.
// All three, because on a shared 2-core machine any one alone flags plain re-runs.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace pathlet::cli::bench {

constexpr double kMaxP = 0.05;

struct CompareResult {
    std::string machine;  // what the calibrations say about the machine's speed (one line), or ""
    std::string table;    // printable
    int regressions = 0, improvements = 0, compared = 0;
    std::vector<std::string> missing;  // in the baseline, not in the current results
};

// `baseline` and `current`: bench reports (an object with "runs", or the older plain array).
// threshold: relative, 0.5 = 50 % slower.
CompareResult compare_reports(const nlohmann::json& baseline, const nlohmann::json& current, double threshold);

// One-sided Mann-Whitney U test: the probability of samples `b` ranking at least this far above
// `a` if both came from one distribution (normal approximation with the tie correction).
double rank_test_greater(const std::vector<double>& b, const std::vector<double>& a);

}  // namespace pathlet::cli::bench
