#include <gtest/gtest.h>

#include "ao_error.hpp"

using namespace pathlet::quality;

TEST(AoError, MaeAndCorrelationOverLinePixelsOnly) {
  FrameSample f;
  f.width = 4; f.height = 1;
  f.ao = {0.2f, 0.4f, 0.6f, 0.9f};
  f.line_id = {1, 1, 1, -1};
  f.depth = {0.5f, 0.5f, 0.5f, 1.0f};
  const std::vector<float> ref = {0.3f, 0.5f, 0.7f, 0.0f};  // shifted by 0.1, background differs
  const AoError e = measure_ao_error(f, ref);
  EXPECT_EQ(e.pixels, 3u);
  EXPECT_NEAR(e.mae, 0.1, 1e-6);
  EXPECT_NEAR(e.correlation, 1.0, 1e-6);
  EXPECT_EQ(e.abs_error[3], 0.0f);
  const AoError inv = measure_ao_error(f, {0.7f, 0.5f, 0.3f, 0.0f});
  EXPECT_NEAR(inv.correlation, -1.0, 1e-6);
  EXPECT_THROW(measure_ao_error(f, {0.1f}), std::invalid_argument);
}
