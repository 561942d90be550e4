#pragma once
// AO error against a reference: mean absolute error and Pearson
// correlation over the pixels covered by a line, plus a per-pixel |error| image.
#include "frame_sample.hpp"

namespace pathlet::quality {

struct AoError {
  std::size_t pixels = 0;
  double mae = 0;
  double correlation = 0;       // Pearson; 0 when either side is constant
  std::vector<float> abs_error;  // per pixel, 0 on background
};

// `reference` holds one AO value per pixel of `frame` (ignored where line_id < 0).
AoError measure_ao_error(const FrameSample& frame, const std::vector<float>& reference);

}  // namespace pathlet::quality
