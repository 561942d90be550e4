// pathlet phantom --preset study|small -o OUT: the synthetic aortic-arch data set.
#include "commands.hpp"
#include "data_outputs.hpp"
#include "common/fraction_progress.hpp"
#include "phantom/phantom.hpp"

#include <cstdio>

namespace pathlet::cli {
namespace {

int run(const std::vector<std::string>& argv) {
    Args a("phantom", "Generates the synthetic aortic-arch phantom: ascending aorta, arch and descending aorta\n"
                      "(radius 11-14 mm, world units mm) with a saccular aneurysm, pulsatile parabolic flow (60 bpm),\n"
                      "helical flow in the arch and a vortex in the aneurysm; traced like real data. Deterministic:\n"
                      "the same bytes on every run and thread count. 'study' matches the study data set (about\n"
                      "3169 lines, 644k points, 18 s); 'small' has a few hundred lines for tests.\n"
                      "Exit status: 0 ok, 1 failure writing, 2 bad usage.");
    std::string preset = "study";
    DataOutputs out;
    bool no_aneurysm = false;
    int threads = 0;
    a.option("preset", preset, "NAME[:density=N]", "study or small; ':density=N' gives N times the lines (N in 1..64)");
    out.declare(a, "also write the vessel wall (.glb/.gltf/.stl/.obj)");
    a.flag("no-aneurysm", no_aneurysm, "leave out the aneurysm")
        .option("threads", threads, "N", "worker threads (0: all cores; the result is the same)")
        .example("pathlet phantom -o study.vtp --wall study.glb", "the study-sized phantom and its wall")
        .example("pathlet phantom --preset small -o small.pathlet", "a small one for quick looks")
        .example("pathlet phantom --preset study:density=16 -o dense.pathlet", "16 times the study's lines (10M points)");
    if (!a.parse(argv)) return 0;
    out.check();  // before minutes of tracing
    phantom::PhantomOptions o;
    try {
        o = phantom::phantom_preset(preset);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    o.aneurysm = !no_aneurysm;
    o.trace.threads = threads;
    FractionProgress progress("phantom");
    trace::TraceStats st;
    const Scene s = phantom::make_phantom(o, progress.callback(), &st);
    if (s.mesh) out.write_wall(*s.mesh);
    out.write_lines(s.lines);
    progress.finish("done");
    std::fprintf(stderr, "pathlet phantom: %s: %zu lines, %zu points, %zu wall triangles; %.1f s\n", o.preset.c_str(),
                 s.lines.line_count(), s.lines.point_count(), s.mesh ? s.mesh->index.size() / 3 : 0, progress.seconds());
    return 0;
}

PATHLET_COMMAND("phantom", "generate the synthetic aortic-arch pathline phantom (study or small preset)", run);

}  // namespace
}  // namespace pathlet::cli
