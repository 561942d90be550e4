#include <gtest/gtest.h>

#include <random>

#include "flicker.hpp"

using namespace pathlet::quality;

namespace {
// A frame with a band of line 7 across the middle rows and a smooth AO ramp on it.
FrameSample band_frame(int w, int h) {
  FrameSample f;
  f.width = w; f.height = h;
  f.ao.assign(f.size(), 1.0f);
  f.line_id.assign(f.size(), -1);
  f.depth.assign(f.size(), 1.0f);
  for (int y = h / 4; y < 3 * h / 4; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      f.line_id[i] = 7;
      f.depth[i] = 0.4f;
      f.ao[i] = 0.3f + 0.5f * float(x) / float(w);
    }
  return f;
}
FrameSample with_noise(FrameSample f, float amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-amplitude, amplitude);
  for (size_t i = 0; i < f.size(); ++i)
    if (f.line_id[i] >= 0) f.ao[i] += u(rng);
  return f;
}
}  // namespace

TEST(Flicker, ZeroOnStaticScene) {
  const FrameSample f = band_frame(32, 16);
  const FlickerStats s = measure_flicker(std::vector<FrameSample>{f, f, f, f}, 0.01f);
  EXPECT_EQ(s.stable_pixels, 3u * 32 * 8);
  EXPECT_EQ(s.ao_flicker, 0.0);
  EXPECT_EQ(s.geometry_change, 0.0);
}

TEST(Flicker, GrowsWithInjectedNoise) {
  const FrameSample f = band_frame(32, 16);
  double last = 0;
  for (float amp : {0.01f, 0.05f, 0.2f}) {
    std::vector<FrameSample> frames;
    for (unsigned k = 0; k < 4; ++k) frames.push_back(with_noise(f, amp, k + 1));
    const FlickerStats s = measure_flicker(frames, 0.01f);
    EXPECT_GT(s.ao_flicker, last) << "amplitude " << amp;
    // Difference of two uniforms in [-a,a]: mean |d| = 2a/3.
    EXPECT_NEAR(s.ao_flicker, 2.0 * amp / 3.0, 0.15 * amp);
    EXPECT_EQ(s.geometry_change, 0.0);
    last = s.ao_flicker;
  }
}

TEST(Flicker, IgnoresPixelsWhoseGeometryChanged) {
  FrameSample a = band_frame(32, 16), b = a;
  for (int x = 0; x < 32; ++x) {
    const size_t i = size_t(4) * 32 + x;  // first band row: another line, other AO
    b.line_id[i] = 9;
    b.ao[i] = 0.0f;
    const size_t j = size_t(5) * 32 + x;  // second row: depth jump beyond tolerance
    b.depth[j] = 0.6f;
    b.ao[j] = 1.0f;
  }
  const FlickerStats s = measure_flicker(a, b, 0.01f);
  EXPECT_EQ(s.ao_flicker, 0.0);
  EXPECT_EQ(s.stable_pixels, 6u * 32);
  EXPECT_NEAR(s.geometry_change, 2.0 / 8.0, 1e-9);
}

TEST(Flicker, RejectsMismatchedFrames) {
  FrameSample a = band_frame(8, 8), b = band_frame(8, 4);
  EXPECT_THROW(measure_flicker(a, b, 0.01f), std::invalid_argument);
  EXPECT_THROW(measure_flicker(std::vector<FrameSample>{a}, 0.01f), std::invalid_argument);
}

// AO that follows the reference frame by frame has no excess flicker however much it
// changes; AO that stands still has the reference's whole change as excess.
TEST(Flicker, AgainstReferenceSeparatesChangeFromNoise) {
  std::vector<FrameSample> frames;
  std::vector<std::vector<float>> ref;
  for (int k = 0; k < 4; ++k) {
    FrameSample f = band_frame(32, 16);
    for (size_t i = 0; i < f.size(); ++i)
      if (f.line_id[i] >= 0) f.ao[i] -= 0.05f * float(k);  // the scene darkens by 0.05 a frame
    ref.push_back(f.ao);
    frames.push_back(f);
  }
  ReferenceFlicker follows = measure_flicker_against(frames, ref, 0.01f);
  EXPECT_NEAR(follows.reference_change, 0.05, 1e-6);
  EXPECT_NEAR(follows.excess, 0.0, 1e-6);
  EXPECT_NEAR(measure_flicker(frames, 0.01f).ao_flicker, 0.05, 1e-6) << "the plain measure counts the change";

  std::vector<FrameSample> still(4, band_frame(32, 16));
  EXPECT_NEAR(measure_flicker_against(still, ref, 0.01f).excess, 0.05, 1e-6);

  std::vector<FrameSample> noisy;
  for (int k = 0; k < 4; ++k) {
    FrameSample f = with_noise(frames[size_t(k)], 0.02f, unsigned(k + 1));
    noisy.push_back(f);
  }
  const double excess = measure_flicker_against(noisy, ref, 0.01f).excess;
  EXPECT_GT(excess, 0.01);
  EXPECT_LT(excess, 0.03);
  EXPECT_THROW(measure_flicker_against(frames, {ref[0]}, 0.01f), std::invalid_argument);
}
