#pragma once
// Ray-traced ambient occlusion reference (issue 13, measure c): the visible pathlets as round
// tubes (Embree round linear curves with the line radius), cosine-weighted hemisphere rays of a
// maximum distance. AO = fraction of rays that escape, the same convention as the screen-space
// term (1 = open). Cosine weighting makes the plain hit fraction the cosine-weighted estimate.
#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace pathlet::quality {

struct Tube {
  std::vector<glm::vec3> points;  // polyline, at least two points
  float radius = 0;
  int id = -1;  // the line it belongs to (ambient() may leave one line out)
};

class RayTracedAo {
 public:
  // False in a build without Embree (PATHLET_WITH_EMBREE=OFF: rt_ao_absent.cpp), where the
  // constructor throws what in_this_build() says.
  static bool in_this_build();
  // Throws std::runtime_error saying the reference is not in this build, unless it is.
  static void require();
  explicit RayTracedAo(const std::vector<Tube>& tubes);
  ~RayTracedAo();
  RayTracedAo(const RayTracedAo&) = delete;
  RayTracedAo& operator=(const RayTracedAo&) = delete;

  // Ambient term at `p` (on a surface with normal `n`, outward) from `rays` cosine-weighted rays
  // no longer than `max_distance`. Deterministic for a given seed.
  // Rays ignore the tubes whose id is `exclude_id` (the point's own line; -1: none).
  float ambient(const glm::vec3& p, const glm::vec3& n, int rays, float max_distance,
                uint32_t seed = 1, int exclude_id = -1) const;
  size_t segments() const { return segments_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<int> segment_id_;  // tube id of each segment (Embree primitive)
  size_t segments_ = 0;
};

// Cosine-weighted direction around unit normal n from two uniforms in [0,1).
glm::vec3 cosine_direction(const glm::vec3& n, float u1, float u2);

}  // namespace pathlet::quality
