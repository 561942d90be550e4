// pathlet info FILE: what a pathline or mesh file holds, and what the importer repaired.
#include "commands.hpp"
#include "common_options.hpp"
#include "common/point_memory.hpp"
#include "common/scene_source.hpp"
#include "io/file_info.hpp"

#include "build_info.hpp"
#include "gl_context.hpp"
#include "runtime.hpp"

#include <pathlet/gl_limits.hpp>

#include <algorithm>
#include <cstdio>
#include <string>

namespace pathlet::cli {
namespace {

// `info --gl`: one NAME VALUE a line, for scripts (scripts/gpu-check.sh) as much as for people.
int print_gl_limits() {
    try {
        Runtime rt;
        GlContext& gl = rt.ensure_gl(/*quiet=*/true);
        const GlLimits& limits = gl_limits();
        std::printf("GL_RENDERER %s\nGL_VERSION %s\nPATHLET_GL_LIMITS %s\n", gl.renderer().c_str(), gl.version().c_str(),
                    limits.minimum_mode() ? "minimum" : "context");
        for (const GlLimit& l : gl_limit_table()) std::printf("%s %d\n", l.name, limits.get(l.pname));
        // What this build is and where it runs from (pathlet --version), one line, so a report
        // from a GPU node says which bundle made it.
        std::string build = build_description();
        std::replace(build.begin(), build.end(), '\n', ';');
        std::printf("PATHLET_VERSION %s\nPATHLET_BUILD %s\n", PATHLET_VERSION, build.c_str());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pathlet info: error: %s\n", e.what());
        return 1;
    }
}

int run(const std::vector<std::string>& argv) {
    Args a("info", "Summarises a pathline or mesh file: format, lines, points, arrays, time span, speed range,\n"
                   "bounds, points per line (min/median/max) and every repair the importer made. Meshes show\n"
                   "vertices, triangles and bounds. The format is sniffed from the content; extensions are hints.\n"
                   "Pathlines: VTK legacy .vtk (ASCII/BINARY, 4.2 and 5.1), VTK XML .vtp (ascii, base64, appended,\n"
                   "zlib), .pathlet caches, plain-text rows 'x y z x y z ...', tractography TrackVis .trk and MRtrix\n"
                   ".tck. Meshes: .gltf/.glb, .stl, .obj. Units are shown where the file says them (VTK field data\n"
                   "LengthUnit/TimeUnit/VelocityUnit, .pathlet, tracts in mm) or --units gives them.\n"
                   "With --gl instead of a file: the GL renderer and every limit the engine works within, one\n"
                   "'NAME VALUE' a line (PATHLET_GL_LIMITS=minimum: the GL 4.5 minimum of each).\n"
                   "Pathlines also show the GPU memory their points take ('gpu points': bytes a point by buffer\n"
                   "and the total; PATHLET_POINT_LAYOUT=exact for unquantised positions).\n"
                   "Exit status: 0 ok, 1 the file cannot be read (message on stderr), 2 bad usage.");
    std::string file;
    bool gl = false;
    Given<std::string> phantom{"study"};
    ArrayOptions arrays;
    a.positional("FILE", file, "pathline or mesh file", /*required=*/false);
    a.flag("gl", gl, "print the GL renderer and the limits the engine uses (binding points, units, sizes)");
    a.option("phantom", phantom, "study|small[:density=N]", "describe the built-in phantom instead of a file");
    arrays.declare(a);
    a.example("pathlet info flow.vtp", "summary of a VTK XML pathline file")
        .example("pathlet info blood_flow --time-step 0.005", "plain-text rows sampled every 5 ms")
        .example("pathlet info lines.vtk --time-array IntegrationTime", "name the time array explicitly")
        .example("pathlet info aorta-surface.stl", "vertices, triangles and bounds of a vessel wall")
        .example("pathlet info tracks300.trk", "TrackVis tractography: header, tracks, scalars and properties")
        .example("pathlet info blood_flow --time-step 0.005 --units mm", "text rows in mm, so speeds in mm/s")
        .example("pathlet info --gl", "the GL renderer and limits (PATHLET_GL_LIMITS=minimum: a minimal GL 4.5 driver)")
        .example("pathlet info --phantom study:density=16", "the phantom 16 times denser: lines, points, GPU memory");
    if (!a.parse(argv)) return 0;
    if (gl) {
        if (!file.empty()) throw UsageError("give FILE or --gl, not both");
        return print_gl_limits();
    }
    // What the GPU would hold of the lines, by the sizes GpuScene::upload allocates.
    const io::DescribeMore gpu = [](const Pathlines& p) {
        const GpuScene::PointLayout layout = GpuScene::default_point_layout();
        return "gpu points: " + point_memory_text(point_memory_of(p, layout), layout) + "\n";
    };
    if (phantom.given) {
        if (!file.empty()) throw UsageError("give FILE or --phantom, not both");
        SceneSource src;
        src.phantom = phantom.value;
        const Scene scene = load_scene(src, /*quiet=*/true);
        std::printf("file:      %s\n%s", scene.source.c_str(), io::describe_pathlines(scene.lines, {}, gpu).c_str());
        return 0;
    }
    if (file.empty()) throw UsageError("missing FILE (or --gl)");
    const io::LoadOptions opts = arrays.load_options();
    try {
        std::fputs(io::describe_file(file, opts, gpu).c_str(), stdout);
        return 0;
    } catch (const DataError& e) {
        std::fprintf(stderr, "pathlet info: error: %s\n", e.what());
        return 1;
    }
}

PATHLET_COMMAND("info", "describe a pathline or mesh file (format, counts, ranges, repairs)", run);

}  // namespace
}  // namespace pathlet::cli
