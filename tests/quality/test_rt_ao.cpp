#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rt_ao.hpp"

using namespace pathlet::quality;

namespace {
// Two long tubes parallel to x at y = ±c, height h above a surface point at the origin (normal +z).
constexpr float kC = 1.0f, kH = 1.0f, kR = 0.3f, kLen = 60.0f;
std::vector<Tube> two_tubes() {
  return {Tube{{{-kLen, -kC, kH}, {kLen, -kC, kH}}, kR}, Tube{{{-kLen, kC, kH}, {kLen, kC, kH}}, kR}};
}
// Cosine-weighted view factor of an infinite cylinder seen from a differential strip parallel to
// it (Nusselt, 2D): (sin(a + b) - sin(a - b)) / 2, a = angle to the axis from the normal,
// b = half the angle the cylinder subtends.
double closed_form_ambient() {
  const double d = std::hypot(kC, kH), a = std::atan2(kC, kH), b = std::asin(kR / d);
  const double one = 0.5 * (std::sin(a + b) - std::sin(a - b));
  return 1.0 - 2.0 * one;
}
// Brute force: the same cosine rays against the two cylinders, solved analytically in the yz plane.
double brute_force_ambient(int rays, float max_distance) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int open = 0;
  for (int i = 0; i < rays; ++i) {
    const glm::vec3 d = cosine_direction({0, 0, 1}, u(rng), u(rng));
    bool hit = false;
    for (float cy : {-kC, kC}) {
      const double a = d.y * d.y + d.z * d.z, b = -2.0 * (d.y * cy + d.z * kH),
                   c = cy * cy + kH * kH - kR * kR, disc = b * b - 4 * a * c;
      if (a < 1e-12 || disc < 0) continue;
      const double t = (-b - std::sqrt(disc)) / (2 * a);
      if (t > 0 && t <= max_distance) hit = true;
    }
    open += !hit;
  }
  return double(open) / rays;
}
}  // namespace

TEST(RayTracedAo, OpenSkyIsOne) {
  RayTracedAo rt({});
  EXPECT_EQ(rt.ambient({0, 0, 0}, {0, 0, 1}, 256, 10.0f), 1.0f);
}

TEST(RayTracedAo, PointBetweenTwoTubesMatchesClosedFormAndBruteForce) {
  RayTracedAo rt(two_tubes());
  EXPECT_EQ(rt.segments(), 2u);
  const int rays = 1 << 17;  // standard error ~0.0013 at AO ~0.6
  const float ao = rt.ambient({0, 0, 0}, {0, 0, 1}, rays, 50.0f);
  const double exact = closed_form_ambient();
  EXPECT_GT(exact, 0.3);
  EXPECT_LT(exact, 0.9);
  EXPECT_NEAR(ao, exact, 0.006) << "closed form " << exact;
  // With a short maximum distance only the near parts of the tubes occlude: brute force.
  const float short_ao = rt.ambient({0, 0, 0}, {0, 0, 1}, rays, 1.2f);
  const double brute = brute_force_ambient(rays, 1.2f);
  EXPECT_NEAR(short_ao, brute, 0.006);
  EXPECT_GT(short_ao, ao + 0.02) << "a shorter reach must occlude less";
}

TEST(RayTracedAo, ConvergesWithRayCount) {
  RayTracedAo rt(two_tubes());
  const double exact = closed_form_ambient();
  double err_few = 0, err_many = 0;
  for (uint32_t seed = 1; seed <= 16; ++seed) {
    err_few += std::fabs(rt.ambient({0, 0, 0}, {0, 0, 1}, 64, 50.0f, seed) - exact);
    err_many += std::fabs(rt.ambient({0, 0, 0}, {0, 0, 1}, 4096, 50.0f, seed) - exact);
  }
  // 64x the rays: about 8x less error; demand at least 4x.
  EXPECT_LT(err_many * 4, err_few) << err_few / 16 << " vs " << err_many / 16;
}

// A point inside its own tube (where the G-buffer's tube depth puts inclined lines) is
// occluded by that tube's inside unless the tube's line is left out; other lines still count.
TEST(RayTracedAo, LeavesTheOwnLineOut) {
  std::vector<Tube> tubes = two_tubes();
  tubes[0].id = 3;
  tubes[1].id = 4;
  tubes.push_back(Tube{{{-kLen, 0.0f, 0.0f}, {kLen, 0.0f, 0.0f}}, kR, 5});  // the point's own line
  RayTracedAo rt(tubes);
  const glm::vec3 inside{0.0f, 0.0f, 0.5f * kR}, n{0, 0, 1};
  EXPECT_EQ(rt.ambient(inside, n, 4096, 50.0f), 0.0f) << "every ray meets the own tube's inside";
  const float without_own = rt.ambient(inside, n, 1 << 15, 50.0f, 1, 5);
  EXPECT_NEAR(without_own, closed_form_ambient(), 0.02) << "the two other tubes alone";
  EXPECT_LT(rt.ambient(inside, n, 1 << 15, 50.0f, 1, 3), 0.05f) << "leaving another line out keeps the own tube";
}
