// The one classic 4th-order Runge-Kutta step for dp/dt = v(p, t). dt may be negative
// (backward integration).
#pragma once

#include <glm/glm.hpp>

namespace pathlet::trace {

// k1 = v(p, t), passed in because the caller already has it (saves a quarter of the work).
template <class VelocityFn>
glm::vec3 rk4_step(const VelocityFn& v, glm::vec3 p, float t, float dt, glm::vec3 k1) {
    const glm::vec3 k2 = v(p + 0.5f * dt * k1, t + 0.5f * dt);
    const glm::vec3 k3 = v(p + 0.5f * dt * k2, t + 0.5f * dt);
    const glm::vec3 k4 = v(p + dt * k3, t + dt);
    return p + dt / 6.0f * (k1 + 2.0f * k2 + 2.0f * k3 + k4);
}

template <class VelocityFn>
glm::vec3 rk4_step(const VelocityFn& v, glm::vec3 p, float t, float dt) {
    return rk4_step(v, p, t, dt, v(p, t));
}

}  // namespace pathlet::trace
