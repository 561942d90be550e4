#include "flow_sampler.hpp"

#include <algorithm>
#include <cmath>

namespace pathlet::trace {

FlowSampler::FlowSampler(const VelocityField& field, bool periodic, std::optional<Pulsatile> pulse)
    : field_(field), periodic_(periodic), pulse_(pulse) {}

glm::vec3 FlowSampler::velocity(glm::vec3 p, float t) const {
    const TrilinearCell cell(field_.grid, p);
    const auto& times = field_.frame_times;
    const size_t n = field_.frames.size();
    glm::vec3 v;
    if (n == 1) {
        v = cell.sample(field_.frames[0].data());
    } else {
        // Frame pair (a, b) and blend w for time t.
        size_t a = 0, b = 0;
        float w = 0.0f;
        if (periodic_) {
            const float cycle = field_.cycle(), t0 = times.front();
            float u = std::fmod(t - t0, cycle);
            if (u < 0.0f) u += cycle;
            u += t0;
            a = size_t(std::upper_bound(times.begin(), times.end(), u) - times.begin()) - 1;
            b = (a + 1) % n;
            const float tb = b == 0 ? t0 + cycle : times[b];
            w = (u - times[a]) / (tb - times[a]);
        } else if (t <= times.front()) {
            a = b = 0;
        } else if (t >= times.back()) {
            a = b = n - 1;
        } else {
            a = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
            b = a + 1;
            w = (t - times[a]) / (times[b] - times[a]);
        }
        const glm::vec3 va = cell.sample(field_.frames[a].data());
        v = a == b ? va : va + (cell.sample(field_.frames[b].data()) - va) * std::clamp(w, 0.0f, 1.0f);
    }
    return pulse_ ? v * pulse_->factor(t) : v;
}

bool FlowSampler::inside(glm::vec3 p) const {
    if (!field_.grid.contains(p)) return false;
    if (field_.mask.empty()) return true;
    return TrilinearCell(field_.grid, p).sample(field_.mask.data()) >= 0.5f;
}

}  // namespace pathlet::trace
