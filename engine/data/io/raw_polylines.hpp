// What the VTK readers produce before the shared validation/repair step: points, named
// point arrays and VTK-style line topology (offsets into a connectivity list).
#pragma once

#include "pathline_io.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace pathlet::io {

struct RawArray {
    std::string name;
    int components = 1;
    std::vector<float> values;  // tuples * components
};

struct RawPolylines {
    std::vector<float> points;            // xyz
    std::vector<int64_t> offsets{0};      // line i = connectivity[offsets[i] .. offsets[i+1])
    std::vector<int64_t> connectivity;
    std::vector<RawArray> point_arrays;
    Units units;                          // from the dataset's field data
    uint64_t polygons = 0;                // polygons/strips seen (for "this is a surface" errors)
    std::string where_lines = "byte 0";   // locations for errors found after parsing
    std::string where_data = "byte 0";

    size_t point_count() const { return points.size() / 3; }
    size_t line_count() const { return offsets.size() - 1; }
};

// Appends a piece (VTP files may hold several), shifting its indices.
// Arrays missing from either side are dropped (with a warning).
void append_piece(RawPolylines& dst, RawPolylines&& piece, LoadReport& report);

// Offsets start at 0, never decrease, end at connectivity size; indices < points.
void validate_topology(const RawPolylines& raw, const std::string& file);

// Picks time/velocity arrays (LoadOptions names or automatic), gathers each line's
// points, then runs repair_pathlines(). Errors when neither time nor velocity exists.
Pathlines assemble_pathlines(RawPolylines&& raw, const LoadOptions& opts, LoadReport& report, const std::string& file);

// The one repair/validation step every importer ends with. `lines.time` or
// `lines.velocity` may be empty (derived here, with a warning). Drops non-finite points
// (splitting lines), zero-length segments and one-point lines; orders time along each
// line (a line whose time only decreases is reversed; otherwise points are sorted by
// time and equal-time points dropped). Counts go to report.warnings.
void repair_pathlines(Pathlines& lines, LoadReport& report, const std::string& file);

}  // namespace pathlet::io
