// pathlet info FILE: what a pathline or mesh file holds, and what the importer repaired.
#include "commands.hpp"
#include "common_options.hpp"
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
    std::string file;
    ArrayOptions arrays;
    a.positional("FILE", file, "pathline or mesh file");
    arrays.declare(a);
    a.example("pathlet info flow.vtp", "summary of a VTK XML pathline file")
        .example("pathlet info blood_flow --time-step 0.005", "plain-text rows sampled every 5 ms")
        .example("pathlet info lines.vtk --time-array IntegrationTime", "name the time array explicitly")
        .example("pathlet info aorta-surface.stl", "vertices, triangles and bounds of a vessel wall")
        .example("pathlet info tracks300.trk", "TrackVis tractography: header, tracks, scalars and properties")
        .example("pathlet info blood_flow --time-step 0.005 --units mm", "text rows in mm, so speeds in mm/s");
    if (!a.parse(argv)) return 0;
    const io::LoadOptions opts = arrays.load_options();
    try {
        std::fputs(io::describe_file(file, opts).c_str(), stdout);
        return 0;
    } catch (const DataError& e) {
        std::fprintf(stderr, "pathlet info: error: %s\n", e.what());
        return 1;
    }
}

PATHLET_COMMAND("info", "describe a pathline or mesh file (format, counts, ranges, repairs)", run);

}  // namespace
}  // namespace pathlet::cli
