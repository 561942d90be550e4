// pathlet phantom --preset study|small -o OUT: the synthetic aortic-arch data set.
#include "args.hpp"
#include "util/output_check.hpp"
#include "commands.hpp"
#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
#include "phantom/phantom.hpp"
#include "fraction_progress.hpp"

#include <algorithm>
#include <cstdio>

namespace pathlet::cli {
namespace {

int run(std::vector<std::string> argv) {
    Args a("phantom", "Generates the synthetic aortic-arch phantom: ascending aorta, arch and descending aorta\n"
                      "(radius 11-14 mm, world units mm) with a saccular aneurysm, pulsatile parabolic flow (60 bpm),\n"
                      "helical flow in the arch and a vortex in the aneurysm; traced like real data. Deterministic:\n"
                      "the same bytes on every run and thread count. 'study' matches the study data set (about\n"
                      "3169 lines, 644k points, 18 s); 'small' has a few hundred lines for tests.\n"
                      "Exit status: 0 ok, 1 failure writing, 2 bad usage.");
    a.option("preset", "NAME", "study", "study or small")
        .option("output", "OUT", "", "pathlines to write (.vtp, .vtk, .pathlet); required")
        .short_name('o')
        .option("wall", "OUT.glb", "", "also write the vessel wall (.glb/.gltf/.stl/.obj)")
        .flag("no-aneurysm", "leave out the aneurysm")
        .option("threads", "N", "0", "worker threads (0: all cores; the result is the same)")
        .example("pathlet phantom -o study.vtp --wall study.glb", "the study-sized phantom and its wall")
        .example("pathlet phantom --preset small -o small.pathlet", "a small one for quick looks");
    if (!a.parse(argv)) return 0;
    const std::string out = a.get("output");
    if (out.empty()) throw UsageError("missing -o OUT");
    // Before minutes of tracing: the outputs' folders must be writable and their formats known.
    check_output_file(out, "the pathlines");
    io::format_from_extension(out);
    if (!a.get("wall").empty()) check_output_file(a.get("wall"), "the wall");
    phantom::PhantomOptions o;
    try {
        o = phantom::phantom_preset(a.get("preset"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    o.aneurysm = !a.has("no-aneurysm");
    o.trace.threads = int(a.integer("threads"));
    {
        io::format_from_extension(out);
        FractionProgress progress("phantom");
        trace::TraceStats st;
        const Scene s = phantom::make_phantom(o, progress.callback(), &st);
        if (!a.get("wall").empty() && s.mesh) io::save_mesh(*s.mesh, a.get("wall"));
        io::save_pathlines(s.lines, out, io::format_from_extension(out));
        progress.finish("done");
        std::fprintf(stderr, "pathlet phantom: %s: %zu lines, %zu points, %zu wall triangles; %.1f s\n", o.preset.c_str(),
                     s.lines.line_count(), s.lines.point_count(), s.mesh ? s.mesh->index.size() / 3 : 0, progress.seconds());
        return 0;
    }
}

PATHLET_COMMAND("phantom", "generate the synthetic aortic-arch pathline phantom (study or small preset)", run);

}  // namespace
}  // namespace pathlet::cli
