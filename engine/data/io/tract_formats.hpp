// Tractography as pathline input: TrackVis .trk (v1 and v2 headers, either byte order, the
// voxel-to-RAS matrix and voxel order, per-point scalars and per-track properties) and MRtrix
// .tck (Float32/Float64, LE/BE). Streamlines have no time: every reader ends in the repair
// step's pseudo-time along the arc length (each line from t = 0), so the lines are drawn
// whole (window <= 0) or animate as pathlets moving along them. Length unit: mm (TrackVis
// voxmm / RAS mm, MRtrix scanner space). Scalars and properties are listed in the report
// (name, range) but not drawn.
//
// The writers produce the bytes of both formats for tests and fuzz seeds (Pathlines in RAS
// mm; scalar k of point i = i + k / 10, property k of track j = j + k / 10).
#pragma once

#include "pathline_io.hpp"

#include <glm/glm.hpp>

#include <string>
#include <string_view>

namespace pathlet::io {

Pathlines read_trk(std::string_view bytes, const std::string& file, LoadReport& report);
Pathlines read_tck(std::string_view bytes, const std::string& file, LoadReport& report);

struct TrkWriteOptions {
    int version = 2;                 // 1: no voxel-to-RAS matrix (points stay voxmm)
    bool big_endian = false;
    int scalars = 0;                 // per-point scalars named s0, s1, ...
    int properties = 0;              // per-track properties named p0, p1, ...
    glm::vec3 voxel_size{1.0f};
    glm::ivec3 dims{64};
    glm::mat4 vox_to_ras{1.0f};      // column-major (glm); written row-major as TrackVis does
    std::string voxel_order = "RAS";
    bool write_count = true;         // n_count = the number of tracks (false: 0, "unknown")
};
std::string write_trk(const Pathlines& lines, const TrkWriteOptions& opts = {});

struct TckWriteOptions {
    bool big_endian = false;
    bool float64 = false;
    bool end_marker = true;          // the closing Inf triplet
};
std::string write_tck(const Pathlines& lines, const TckWriteOptions& opts = {});

}  // namespace pathlet::io
