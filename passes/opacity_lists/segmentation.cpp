#include "segmentation.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace opacity_lists {

std::vector<float> arc_lengths(const pathlet::Pathlines& lines) {
    std::vector<float> arc(lines.position.size(), 0.0f);
    for (const pathlet::LineRange& r : lines.lines) {
        double a = 0.0;
        for (uint32_t k = r.first + 1; k < r.first + r.count; ++k) {
            const float step = glm::length(lines.position[k] - lines.position[k - 1]);  // as GpuScene sums it
            if (std::isfinite(step)) a += step;
            arc[k] = float(a);
        }
    }
    return arc;
}

Segmentation segment_lines(const pathlet::Pathlines& lines, const std::vector<float>& arc, float length) {
    Segmentation s;
    for (size_t l = 0; l < lines.lines.size(); ++l) {
        const pathlet::LineRange& r = lines.lines[l];
        const float total = r.count > 0 ? arc[r.first + r.count - 1] : 0.0f;
        const double n = length > 0.0f ? std::round(double(total) / double(length)) : 1.0;
        const uint32_t count = uint32_t(std::clamp(n, 1.0, 1e7));
        s.first.push_back(uint32_t(s.line.size()));
        s.count.push_back(count);
        s.length.push_back(total > 0.0f ? total / float(count) : 0.0f);
        s.line.insert(s.line.end(), count, uint32_t(l));
    }
    return s;
}

std::vector<float> segment_means(const pathlet::Pathlines& lines, const std::vector<float>& arc, const Segmentation& s,
                                 const std::vector<float>& value) {
    std::vector<float> out(s.segments(), 0.0f);
    for (size_t l = 0; l < lines.lines.size(); ++l) {
        const pathlet::LineRange& r = lines.lines[l];
        if (r.count == 0) continue;
        const double len = s.length[l];
        if (!(len > 0.0) || r.count < 2) {  // a zero-length line: the mean of its points
            double sum = 0.0;
            for (uint32_t k = r.first; k < r.first + r.count; ++k) sum += value[k];
            std::fill_n(out.begin() + s.first[l], s.count[l], float(sum / r.count));
            continue;
        }
        // Integrate the piecewise-linear field over each segment [j len, (j + 1) len].
        uint32_t k = r.first;  // the point interval [k, k + 1] in use
        for (uint32_t j = 0; j < s.count[l]; ++j) {
            const double a = j * len, b = (j + 1 == s.count[l]) ? double(arc[r.first + r.count - 1]) : (j + 1) * len;
            double sum = 0.0, covered = 0.0;
            while (k + 1 < r.first + r.count - 1 && arc[k + 1] <= a) ++k;
            for (uint32_t i = k; i + 1 < r.first + r.count && arc[i] < b; ++i) {
                const double x0 = arc[i], x1 = arc[i + 1];
                const double lo = std::max(a, x0), hi = std::min(b, x1);
                if (hi <= lo || x1 <= x0) continue;
                auto at = [&](double x) { return value[i] + (value[i + 1] - value[i]) * (x - x0) / (x1 - x0); };
                sum += 0.5 * (at(lo) + at(hi)) * (hi - lo);
                covered += hi - lo;
            }
            out[s.first[l] + j] = covered > 0.0 ? float(sum / covered) : value[k];
        }
    }
    return out;
}

float quantile(std::vector<float> v, double p) {
    v.erase(std::remove_if(v.begin(), v.end(), [](float x) { return !std::isfinite(x); }), v.end());
    if (v.empty()) return 0.0f;
    const size_t i = std::min(v.size() - 1, size_t(std::clamp(p, 0.0, 1.0) * double(v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(i), v.end());
    return v[i];
}

std::vector<uint32_t> pack(const Segmentation& s, uint32_t generation, const std::vector<float>* importance) {
    const uint32_t lines = uint32_t(s.first.size()), segments = uint32_t(s.segments());
    const uint32_t per_segment = kHeaderWords + 4 * lines;
    const uint32_t groups = (std::max(segments, per_segment) + kGroup - 1) / kGroup;
    std::vector<uint32_t> b{lines, segments, generation, per_segment, groups, 1, 1, 0};
    b.reserve(per_segment + segments * (importance ? 2 : 1));
    for (uint32_t l = 0; l < lines; ++l) {
        uint32_t bits = 0;
        std::memcpy(&bits, &s.length[l], 4);
        b.insert(b.end(), {s.first[l], s.count[l], bits, 0u});
    }
    b.insert(b.end(), s.line.begin(), s.line.end());
    if (importance)
        for (float g : *importance) {
            uint32_t bits = 0;
            std::memcpy(&bits, &g, 4);
            b.push_back(bits);
        }
    return b;
}

}  // namespace opacity_lists
