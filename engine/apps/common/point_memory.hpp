// The GPU memory of a scene's line points, in the words `info`, `graph --plan` and `bench` print.
#pragma once

#include <pathlet/gpu_scene.hpp>

#include <string>

namespace pathlet {

// What GpuScene::upload allocates for `lines` with `layout` (the same sizes, without GL).
GpuScene::PointMemory point_memory_of(const Pathlines& lines, GpuScene::PointLayout layout);
// "24.3 B a point (positions 8, attributes 16, level of detail 4, chunks 1.3), 15.2 MiB for
// 623,214 points (quantised)": one line, no newline.
std::string point_memory_text(const GpuScene::PointMemory& m, GpuScene::PointLayout layout);

}  // namespace pathlet
