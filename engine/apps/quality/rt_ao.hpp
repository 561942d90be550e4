#pragma once
// Ray-traced ambient occlusion reference (issue 13, measure c): the visible pathlets as round
// tubes (Embree round linear curves with the line radius), cosine-weighted hemisphere rays of a
// maximum distance. AO = fraction of rays that escape, the same convention as the screen-space
// term (1 = open). Cosine weighting makes the plain hit fraction the cosine-weighted estimate.
#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <utility>
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
  // Where the ray from `origin` along unit `dir` first meets a tube of line `id` (the others are
  // transparent to it), and the tube's outward unit normal there. A ray that passes the tube by
  // (a rim pixel a little outside it: the drawn line is simplified within the level of detail)
  // gets the tube's rim nearest to the ray. False when the line has no tube here.
  bool surface_of(int id, const glm::vec3& origin, const glm::vec3& dir, glm::vec3& point, glm::vec3& normal) const;
  size_t segments() const { return segments_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<int> segment_id_;  // tube id of each segment (Embree primitive)
  std::vector<glm::vec3> segment_a_, segment_b_;  // its end points (the axis, for surface_of's normal)
  std::vector<float> segment_radius_;
  std::unordered_map<int, std::pair<size_t, size_t>> segments_of_;  // tube id -> first segment, count
  size_t segments_ = 0;
};

// Cosine-weighted direction around unit normal n from two uniforms in [0,1).
glm::vec3 cosine_direction(const glm::vec3& n, float u1, float u2);

}  // namespace pathlet::quality
