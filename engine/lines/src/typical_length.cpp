// The typical length of a pathlet, the unit of the kit's arc-length measures (u_typical_length,
// line_fade.glsl's fade_measure = arc_length).
#include <pathlet/lines.hpp>

#include <algorithm>
#include <cmath>

namespace pathlet::lines {

// Median speed x window, or with whole lines the median line length.
float typical_pathlet_length(const Scene& s, float window) {
    const auto& pl = s.lines;
    std::vector<float> v;
    if (window > 0.0f) {
        for (const auto& u : pl.velocity)
            if (float sp = glm::length(u); std::isfinite(sp)) v.push_back(sp);
    } else {
        for (const auto& r : pl.lines) {
            double len = 0;
            for (uint32_t k = 1; k < r.count; ++k)
                if (float d = glm::length(pl.position[r.first + k] - pl.position[r.first + k - 1]); std::isfinite(d))
                    len += d;
            v.push_back(float(len));
        }
    }
    if (v.empty()) return 1.0f;
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    float m = v[v.size() / 2] * (window > 0.0f ? window : 1.0f);
    return m > 0.0f ? m : 1.0f;
}

}  // namespace pathlet::lines
