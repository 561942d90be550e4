// The ray-traced AO reference's stand-in in a build without Embree (PATHLET_WITH_EMBREE=OFF, the
// lean bundle): `pathlet quality` and pathlet.quality say it is not in this build, before any work.
#include "rt_ao.hpp"

#include <stdexcept>

namespace pathlet::quality {

struct RayTracedAo::Impl {};

bool RayTracedAo::in_this_build() { return false; }

void RayTracedAo::require() {
  throw std::runtime_error(
      "the ray-traced AO reference of quality is not in this build (built without Embree: PATHLET_WITH_EMBREE=OFF, "
      "as the lean bundle is); measure quality with the full build or the default bundle");
}

RayTracedAo::RayTracedAo(const std::vector<Tube>&) { require(); }
RayTracedAo::~RayTracedAo() = default;

float RayTracedAo::ambient(const glm::vec3&, const glm::vec3&, int, float, uint32_t, int) const { return 1.0f; }

bool RayTracedAo::surface_of(int, const glm::vec3&, const glm::vec3&, glm::vec3&, glm::vec3&) const { return false; }

glm::vec3 cosine_direction(const glm::vec3& n, float, float) { return n; }

}  // namespace pathlet::quality
