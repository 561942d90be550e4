#pragma once
// One rendered frame as the quality measures see it: per-pixel AO, line id and linear depth.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pathlet::quality {

struct FrameSample {
  int width = 0, height = 0;
  std::vector<float> ao;         // ambient term in [0,1] (1 = unoccluded)
  std::vector<int32_t> line_id;  // < 0: background
  std::vector<float> depth;      // linear depth (eye_depth - near) / (far - near)
  std::size_t size() const { return static_cast<std::size_t>(width) * height; }
};

}  // namespace pathlet::quality
