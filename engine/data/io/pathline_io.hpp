// Pathline import/export: VTK legacy (.vtk), VTK XML PolyData (.vtp), plain-text rows
// (one pathline per row), the native binary cache (.pathlet), and as inputs tractography:
// TrackVis .trk and MRtrix .tck (io/tract_formats.hpp). Format is chosen by
// content first (sniffing), then by extension. All failures throw pathlet::DataError
// with "<file>: line N: ..." or "<file>: byte N: ...".
//
// Every importer ends in the same repair step (io/raw_polylines.hpp), which warns with counts:
//  * NaN/inf points are dropped and their line split there; lines left with < 2 points dropped.
//  * Duplicate consecutive points (within 1e-6 of the data diagonal) are dropped.
//  * Time along a line: only decreasing -> the line is reversed; otherwise out of order ->
//    points are stably sorted by time; points repeating the previous time are dropped.
//  * No time array but velocity: time from arc length / speed (each line starts at 0).
//    Neither: DataError listing the arrays present and naming LoadOptions/--time-array, or
//    with LoadOptions::streamlines (always for tractography) timeless lines drawn whole, with a
//    pseudo-time along the arc length (LoadOptions::pseudo_time animates them along it).
//  * No velocity: finite differences of position over time.
//  * An empty dataset (no lines) loads as empty Pathlines with a warning, not an error.
//  * PolyData with polygons and no lines (a surface .vtp) is a DataError pointing to meshes.
// Units (Pathlines::units) come from VTK field data (LengthUnit, TimeUnit, VelocityUnit string
// arrays), the native cache, or LoadOptions::units; writers write the known ones back.
// Writers: VTK legacy is written in the 4.2 layout (readable by every VTK); .vtp as
// UInt64-header, little-endian, time/velocity Float32; all output goes through
// write_file_atomic (never half-written).
#pragma once

#include <pathlet/scene.hpp>

#include <string>
#include <vector>

namespace pathlet::io {

struct LoadOptions {
    std::string time_array;      // "" = auto ("time","Time","t","IntegrationTime", case-insensitive)
    std::string velocity_array;  // "" = auto ("velocity","Velocity","vel","U","v")
    double time_step = 0.0;      // plain-text rows: seconds between samples; 0 = 1/100 s default
    // Lines with neither time nor velocity (streamlines, centrelines) load as timeless lines,
    // drawn whole (Pathlines::timeless), instead of an error; tractography files always do.
    bool streamlines = false;
    // Timeless lines animate: their pseudo-time along the arc length (10 % of the diagonal per
    // second) becomes their time, so pathlets move along them. Implies `streamlines`.
    bool pseudo_time = false;
    std::string units;           // --units LENGTH[,VELOCITY] over what the file says (io/units.hpp)
};

struct LoadReport {
    std::string format;                  // e.g. "VTK legacy 5.1 BINARY"
    std::vector<std::string> arrays;     // point arrays found, "name (N comp)"
    std::vector<std::string> warnings;   // repairs made, e.g. "dropped 12 NaN points in 3 lines"
};

enum class PathlineFormat { VtkAscii, VtkBinary, VtpAscii, VtpBinary /*inline base64*/, VtpAppendedRaw, VtpAppendedBase64, VtpZlib, Native };

Pathlines load_pathlines(const std::string& path, const LoadOptions& opts = {}, LoadReport* report = nullptr);
void save_pathlines(const Pathlines& lines, const std::string& path, PathlineFormat fmt);
// .vtk -> VtkBinary, .vtp -> VtpZlib, .pathlet -> Native; throws DataError otherwise.
PathlineFormat format_from_extension(const std::string& path);

}  // namespace pathlet::io
