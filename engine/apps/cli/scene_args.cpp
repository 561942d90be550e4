#include "scene_args.hpp"

#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
#include "phantom/phantom.hpp"
#include "fraction_progress.hpp"

#include <cstdio>

namespace pathlet::cli {

void add_scene_options(Args& a) {
    a.option("data", "FILE", "", "pathlines: .vtk (legacy), .vtp, .pathlet, or text rows 'x y z x y z ...'")
        .option("mesh", "FILE", "", "vessel wall: .gltf/.glb, .stl or .obj (optional)")
        .option("phantom", "study|small", "study", "built-in aortic-arch phantom used when --data is not given")
        .option("time-array", "NAME", "", "point array holding time (default: time, Time, t, IntegrationTime)")
        .option("velocity-array", "NAME", "", "point array holding velocity (default: velocity, Velocity, U, v)")
        .option("time-step", "SECONDS", "0", "text rows: seconds between samples (0: 0.01)");
}

SceneSource scene_source(const Args& a) {
    SceneSource s;
    s.data = a.get("data");
    s.mesh = a.get("mesh");
    s.phantom = a.get("phantom");
    s.time_array = a.get("time-array");
    s.velocity_array = a.get("velocity-array");
    s.time_step = a.number("time-step");
    return s;
}

Scene load_scene(const SceneSource& src, bool quiet) {
    Scene scene;
    if (src.data.empty()) {
        // Generated once (tracing takes a while on two cores), then read from the cache.
        FractionProgress bar("phantom '" + src.phantom + "'", quiet);
        scene = phantom::load_or_make_phantom(src.phantom, bar.callback());
        bar.finish(std::to_string(scene.lines.line_count()) + " lines");
    } else {
        io::LoadOptions o;
        o.time_array = src.time_array;
        o.velocity_array = src.velocity_array;
        o.time_step = src.time_step;
        io::LoadReport rep;
        scene.lines = io::load_pathlines(src.data, o, &rep);
        scene.source = src.data;
        for (const auto& w : rep.warnings) std::fprintf(stderr, "warning: %s: %s\n", src.data.c_str(), w.c_str());
    }
    if (!src.mesh.empty()) {
        io::LoadReport rep;
        scene.mesh = io::load_mesh(src.mesh, &rep);
        for (const auto& w : rep.warnings) std::fprintf(stderr, "warning: %s: %s\n", src.mesh.c_str(), w.c_str());
    }
    if (!quiet)
        std::fprintf(stderr, "data: %s — %zu lines, %zu points, t %.2f..%.2f s, speed %.3g..%.3g%s\n", scene.source.c_str(),
                     scene.lines.line_count(), scene.lines.point_count(), scene.lines.time_min(),
                     scene.lines.time_max(), scene.lines.speed_min(), scene.lines.speed_max(),
                     scene.mesh ? (", wall " + std::to_string(scene.mesh->index.size() / 3) + " triangles").c_str() : "");
    return scene;
}

}  // namespace pathlet::cli
