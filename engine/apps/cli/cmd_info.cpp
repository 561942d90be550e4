// pathlet info FILE: what a pathline or mesh file holds, and what the importer repaired.
#include "args.hpp"
#include "commands.hpp"
#include "io/file_info.hpp"
#include "scene_args.hpp"

#include <cstdio>

namespace pathlet::cli {
namespace {

int run(const std::vector<std::string>& argv) {
    Args a("info", "Summarises a pathline or mesh file: format, lines, points, arrays, time span, speed range,\n"
                   "bounds, points per line (min/median/max) and every repair the importer made. Meshes show\n"
                   "vertices, triangles and bounds. The format is sniffed from the content; extensions are hints.\n"
                   "Pathlines: VTK legacy .vtk (ASCII/BINARY, 4.2 and 5.1), VTK XML .vtp (ascii, base64, appended,\n"
                   "zlib), .pathlet caches, plain-text rows 'x y z x y z ...', tractography TrackVis .trk and MRtrix\n"
                   ".tck. Meshes: .gltf/.glb, .stl, .obj. Units are shown where the file says them (VTK field data\n"
                   "LengthUnit/TimeUnit/VelocityUnit, .pathlet, tracts in mm) or --units gives them.\n"
                   "Exit status: 0 ok, 1 the file cannot be read (message on stderr), 2 bad usage.");
    a.positional("FILE", "pathline or mesh file")
        .option("time-array", "NAME", "", "point array holding time (default: time, t, IntegrationTime)")
        .option("velocity-array", "NAME", "", "point array holding velocity (default: velocity, vel, U, v)")
        .option("time-step", "SECONDS", "0", "plain-text rows: seconds between samples (0 = 0.01 s)")
        .option("units", "LENGTH[,VELOCITY]", "", "units where the file does not say them, e.g. mm or m,m/s")
        .flag("streamlines", "VTK lines with neither time nor velocity load as streamlines (drawn whole)")
        .flag("pseudo-time", "lines without time (tracts, --streamlines) animate along a pseudo-time (arc length)")
        .example("pathlet info flow.vtp", "summary of a VTK XML pathline file")
        .example("pathlet info blood_flow --time-step 0.005", "plain-text rows sampled every 5 ms")
        .example("pathlet info lines.vtk --time-array IntegrationTime", "name the time array explicitly")
        .example("pathlet info aorta-surface.stl", "vertices, triangles and bounds of a vessel wall")
        .example("pathlet info tracks300.trk", "TrackVis tractography: header, tracks, scalars and properties")
        .example("pathlet info blood_flow --time-step 0.005 --units mm", "text rows in mm, so speeds in mm/s");
    if (!a.parse(argv)) return 0;
    io::LoadOptions opts;
    opts.time_array = a.get("time-array");
    opts.velocity_array = a.get("velocity-array");
    opts.time_step = a.number("time-step");
    if (opts.time_step < 0) throw UsageError("--time-step must be >= 0");
    opts.units = units_option(a);
    opts.streamlines = a.has("streamlines");
    opts.pseudo_time = a.has("pseudo-time");
    try {
        std::fputs(io::describe_file(a.pos("FILE"), opts).c_str(), stdout);
        return 0;
    } catch (const DataError& e) {
        std::fprintf(stderr, "pathlet info: error: %s\n", e.what());
        return 1;
    }
}

PATHLET_COMMAND("info", "describe a pathline or mesh file (format, counts, ranges, repairs)", run);

}  // namespace
}  // namespace pathlet::cli
