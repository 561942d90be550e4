#include "common/point_memory.hpp"

#include <pathlet/line_chunks.hpp>

#include <cstdio>

namespace pathlet {

GpuScene::PointMemory point_memory_of(const Pathlines& lines, GpuScene::PointLayout layout) {
    LineChunks chunks;
    chunks.build(lines);
    return GpuScene::point_memory(lines.point_count(), chunks.chunks().size(), layout);
}

std::string point_memory_text(const GpuScene::PointMemory& m, GpuScene::PointLayout layout) {
    const double n = double(m.points ? m.points : 1);
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "%.1f B a point (positions %.0f, attributes %.0f, level of detail %.0f, chunks %.1f), %.1f MiB for "
                  "%zu points (%s)",
                  m.per_point(), double(m.positions) / n, double(m.attributes) / n, double(m.lod) / n,
                  double(m.chunk_boxes) / n, double(m.total()) / (1024.0 * 1024.0), m.points, GpuScene::layout_name(layout));
    return buf;
}

}  // namespace pathlet
