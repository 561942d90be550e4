#include "profiler/profiler.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pathlet {

double percentile_sorted(const std::vector<double>& sorted, double p) {
    if (sorted.empty()) return 0;
    double pos = std::clamp(p, 0.0, 1.0) * double(sorted.size() - 1);
    size_t lo = size_t(std::floor(pos));
    size_t hi = std::min(lo + 1, sorted.size() - 1);
    return sorted[lo] + (sorted[hi] - sorted[lo]) * (pos - double(lo));
}

Profiler::Stats compute_stats(std::vector<double> samples) {
    Profiler::Stats s;
    if (samples.empty()) return s;
    std::sort(samples.begin(), samples.end());
    s.n = samples.size();
    s.min = samples.front();
    s.max = samples.back();
    s.mean = std::accumulate(samples.begin(), samples.end(), 0.0) / double(s.n);
    s.median = percentile_sorted(samples, 0.5);
    s.p5 = percentile_sorted(samples, 0.05);
    s.p95 = percentile_sorted(samples, 0.95);
    return s;
}

}  // namespace pathlet
