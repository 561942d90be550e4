// Small analytic velocity fields and masks for the trace tests and the benchmark.
#pragma once

#include "trace/velocity_field.hpp"

#include <functional>

namespace pathlet::test {

// dims points, spacing 1, origin 0; velocity from fn(position).
trace::VelocityField make_field(glm::ivec3 dims, const std::function<glm::vec3(glm::vec3)>& fn, float spacing = 1.0f);
// Mask = 1 inside a sphere (centre, radius), else 0 (stored into field.mask).
void mask_sphere(trace::VelocityField& f, glm::vec3 centre, float radius);
// Signed "inside-ness" of a sphere sampled on the field's grid: radius - distance.
std::vector<float> sphere_values(const trace::Grid& g, glm::vec3 centre, float radius);

}  // namespace pathlet::test
