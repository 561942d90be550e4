// Velocity at (position, time) from a VelocityField: trilinear in space, linear between
// frames in time (wrapping over the cycle when periodic, clamped otherwise), optionally
// scaled by a pulsatile waveform. Read-only, so one instance is shared by all threads.
#pragma once

#include "pulsatile.hpp"
#include "velocity_field.hpp"

#include <optional>

namespace pathlet::trace {

class FlowSampler {
public:
    FlowSampler(const VelocityField& field, bool periodic, std::optional<Pulsatile> pulse);

    glm::vec3 velocity(glm::vec3 p, float t) const;
    // In the grid box and, when there is a mask, where the interpolated mask is >= 0.5.
    bool inside(glm::vec3 p) const;
    const Grid& grid() const { return field_.grid; }

private:
    const VelocityField& field_;
    bool periodic_;
    std::optional<Pulsatile> pulse_;
};

}  // namespace pathlet::trace
