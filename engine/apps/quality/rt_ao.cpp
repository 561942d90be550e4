#include "rt_ao.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pathlet::quality {

struct RayTracedAo::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

bool RayTracedAo::in_this_build() { return true; }
void RayTracedAo::require() {}

RayTracedAo::RayTracedAo(const std::vector<Tube>& tubes) : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice("threads=1");  // the measure runs beside other work; stay frugal
  if (!impl_->device) throw std::runtime_error("ray-traced AO: cannot create an Embree device");
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  std::vector<float> verts;      // x y z r
  std::vector<uint32_t> index;   // first vertex of each segment
  for (const Tube& t : tubes) {
    if (t.points.size() < 2) continue;
    const uint32_t base = uint32_t(verts.size() / 4);
    segments_of_[t.id] = {segment_id_.size(), t.points.size() - 1};
    for (const glm::vec3& p : t.points) verts.insert(verts.end(), {p.x, p.y, p.z, t.radius});
    for (uint32_t i = 0; i + 1 < t.points.size(); ++i) {
      index.push_back(base + i);
      segment_id_.push_back(t.id);
      segment_a_.push_back(t.points[i]);
      segment_b_.push_back(t.points[i + 1]);
      segment_radius_.push_back(t.radius);
    }
  }
  segments_ = index.size();
  if (!index.empty()) {
    RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE);
    float* vb = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                           RTC_FORMAT_FLOAT4, 4 * sizeof(float),
                                                           verts.size() / 4));
    std::copy(verts.begin(), verts.end(), vb);
    uint32_t* ib = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(uint32_t), index.size()));
    std::copy(index.begin(), index.end(), ib);
    rtcCommitGeometry(g);
    rtcAttachGeometry(impl_->scene, g);
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(impl_->scene);
  if (rtcGetDeviceError(impl_->device) != RTC_ERROR_NONE)
    throw std::runtime_error("ray-traced AO: Embree failed to build the tube scene");
}

RayTracedAo::~RayTracedAo() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

glm::vec3 cosine_direction(const glm::vec3& n, float u1, float u2) {
  const float r = std::sqrt(u1), phi = 6.28318530718f * u2;
  const float x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(0.0f, 1 - u1));
  const glm::vec3 a = std::fabs(n.x) > 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 t = glm::normalize(glm::cross(a, n)), b = glm::cross(n, t);
  return x * t + y * b + z * n;
}

// Small counter-based generator (PCG hash): reproducible per seed and ray index.
static float uniform(uint32_t v) {
  uint32_t s = v * 747796405u + 2891336453u;
  uint32_t w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
  w = (w >> 22u) ^ w;
  return float(w >> 8) * (1.0f / 16777216.0f);
}

namespace {
// The intersection context with what the filter needs (Embree passes the context through):
// hits of line `id` are dropped (`keep_only` false: the point's own line) or are the only ones kept.
struct ExcludeContext {
  RTCIntersectContext ctx;
  const std::vector<int>* segment_id;
  int id;
  bool keep_only = false;
};

void filter_by_line(const RTCFilterFunctionNArguments* args) {
  const auto* c = reinterpret_cast<const ExcludeContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    const bool of_id = prim < c->segment_id->size() && (*c->segment_id)[prim] == c->id;
    if (of_id != c->keep_only) args->valid[i] = 0;
  }
}
}  // namespace

float RayTracedAo::ambient(const glm::vec3& p, const glm::vec3& n, int rays, float max_distance,
                           uint32_t seed, int exclude_id) const {
  if (rays <= 0) return 1.0f;
  const glm::vec3 nn = glm::normalize(n);
  ExcludeContext ex{{}, &segment_id_, exclude_id};
  RTCIntersectContext& ctx = ex.ctx;
  rtcInitIntersectContext(&ctx);
  if (exclude_id >= 0) ctx.filter = filter_by_line;
  int open = 0;
  for (int i = 0; i < rays; ++i) {
    const uint32_t k = seed * 0x9E3779B9u + uint32_t(i) * 2u;
    const glm::vec3 d = cosine_direction(nn, uniform(k), uniform(k + 1));
    RTCRay ray{};
    ray.org_x = p.x; ray.org_y = p.y; ray.org_z = p.z;
    ray.dir_x = d.x; ray.dir_y = d.y; ray.dir_z = d.z;
    ray.tnear = 1e-4f * std::max(1.0f, max_distance);
    ray.tfar = max_distance;
    ray.mask = 0xFFFFFFFFu;
    ray.flags = 0;
    rtcOccluded1(impl_->scene, &ctx, &ray);
    if (ray.tfar >= 0) ++open;  // Embree sets tfar to -inf on a hit
  }
  return float(open) / float(rays);
}

namespace {
// The closest points of the ray o + s d (s >= 0, d unit) and the segment a + u (b - a), u in [0, 1].
void closest_ray_segment(const glm::vec3& o, const glm::vec3& d, const glm::vec3& a, const glm::vec3& b, glm::vec3& on_ray,
                         glm::vec3& on_axis) {
  const glm::vec3 ab = b - a, w = o - a;
  const float len2 = glm::dot(ab, ab), bd = glm::dot(ab, d), dw = glm::dot(d, w), abw = glm::dot(ab, w);
  const float den = len2 - bd * bd;  // |ab|^2 sin^2 of the angle between them
  float u = den > 1e-12f * len2 ? std::clamp((abw - bd * dw) / den, 0.0f, 1.0f) : 0.0f;
  float s = std::max(glm::dot(a + u * ab - o, d), 0.0f);
  if (len2 > 0) u = std::clamp(glm::dot(o + s * d - a, ab) / len2, 0.0f, 1.0f);  // one refinement from the ray side
  on_axis = a + u * ab;
  on_ray = o + std::max(glm::dot(on_axis - o, d), 0.0f) * d;
}
}  // namespace

bool RayTracedAo::surface_of(int id, const glm::vec3& origin, const glm::vec3& dir, glm::vec3& point,
                             glm::vec3& normal) const {
  const auto range = segments_of_.find(id);
  if (range == segments_of_.end()) return false;
  ExcludeContext only{{}, &segment_id_, id, true};
  rtcInitIntersectContext(&only.ctx);
  only.ctx.filter = filter_by_line;
  RTCRayHit rh{};
  rh.ray.org_x = origin.x; rh.ray.org_y = origin.y; rh.ray.org_z = origin.z;
  rh.ray.dir_x = dir.x; rh.ray.dir_y = dir.y; rh.ray.dir_z = dir.z;
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &only.ctx, &rh);
  size_t seg = range->second.first;
  glm::vec3 on_ray, on_axis;
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID && rh.hit.primID < segment_a_.size()) {
    seg = rh.hit.primID;
    on_ray = origin + dir * rh.ray.tfar;
    const glm::vec3 a = segment_a_[seg], ab = segment_b_[seg] - a;  // outward from the closest axis point
    on_axis = a + std::clamp(glm::dot(on_ray - a, ab) / std::max(glm::dot(ab, ab), 1e-30f), 0.0f, 1.0f) * ab;
  } else {
    // Missed: the line's segment passing nearest to the ray, and its rim there.
    float best = std::numeric_limits<float>::infinity();
    for (size_t k = range->second.first; k < range->second.first + range->second.second; ++k) {
      glm::vec3 r_pt, a_pt;
      closest_ray_segment(origin, dir, segment_a_[k], segment_b_[k], r_pt, a_pt);
      const float d2 = glm::dot(r_pt - a_pt, r_pt - a_pt);
      if (d2 < best) {
        best = d2;
        seg = k;
        on_ray = r_pt;
        on_axis = a_pt;
      }
    }
    if (!std::isfinite(best)) return false;
  }
  const glm::vec3 out = on_ray - on_axis;
  if (glm::dot(out, out) <= 0) return false;
  normal = glm::normalize(out);
  point = on_axis + segment_radius_[seg] * normal;
  return true;
}

}  // namespace pathlet::quality
