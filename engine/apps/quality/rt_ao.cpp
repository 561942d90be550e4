#include "rt_ao.hpp"

#include <embree3/rtcore.h>

#include <cmath>
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
    for (const glm::vec3& p : t.points) verts.insert(verts.end(), {p.x, p.y, p.z, t.radius});
    for (uint32_t i = 0; i + 1 < t.points.size(); ++i) {
      index.push_back(base + i);
      segment_id_.push_back(t.id);
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
// The intersection context with what the filter needs (Embree passes the context through).
struct ExcludeContext {
  RTCIntersectContext ctx;
  const std::vector<int>* segment_id;
  int exclude;
};

void skip_own_line(const RTCFilterFunctionNArguments* args) {
  const auto* c = reinterpret_cast<const ExcludeContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    if (prim < c->segment_id->size() && (*c->segment_id)[prim] == c->exclude) args->valid[i] = 0;
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
  if (exclude_id >= 0) ctx.filter = skip_own_line;
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

}  // namespace pathlet::quality
