#include "scene_args.hpp"

#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
#include "io/units.hpp"
#include "phantom/phantom.hpp"
#include "fraction_progress.hpp"

#include <cstdio>

namespace pathlet::cli {

void add_scene_options(Args& a) {
    a.option("data", "FILE", "", "pathlines: .vtk (legacy), .vtp, .pathlet, text rows 'x y z x y z ...', or tracts .trk/.tck")
        .option("mesh", "FILE", "", "vessel wall: .gltf/.glb, .stl or .obj (optional)")
        .option("phantom", "study|small", "study", "built-in aortic-arch phantom used when --data is not given")
        .option("time-array", "NAME", "", "point array holding time (default: time, Time, t, IntegrationTime)")
        .option("velocity-array", "NAME", "", "point array holding velocity (default: velocity, Velocity, U, v)")
        .option("time-step", "SECONDS", "0", "text rows: seconds between samples (0: 0.01)")
        .option("units", "LENGTH[,VELOCITY]", "",
                "units of the data where the file does not say them, e.g. mm or m,m/s (velocity default: LENGTH/s when "
                "time is in seconds); shown by the legend")
        .flag("streamlines", "VTK lines with neither time nor velocity (streamlines, centrelines) load as lines drawn whole")
        .flag("pseudo-time", "lines without time (tracts, --streamlines) animate along a pseudo-time (arc length)");
}

std::string units_option(const Args& a) {
    const std::string spec = a.get("units");
    try {
        Units probe;
        io::apply_units_option(probe, spec);  // a bad spec is a usage error before any loading
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    return spec;
}

SceneSource scene_source(const Args& a) {
    SceneSource s;
    s.data = a.get("data");
    s.mesh = a.get("mesh");
    s.phantom = a.get("phantom");
    s.time_array = a.get("time-array");
    s.velocity_array = a.get("velocity-array");
    s.time_step = a.number("time-step");
    s.units = units_option(a);
    s.streamlines = a.has("streamlines");
    s.pseudo_time = a.has("pseudo-time");
    return s;
}

Scene load_scene(const SceneSource& src, bool quiet) {
    Scene scene;
    if (src.data.empty()) {
        // Generated once (tracing takes a while on two cores), then read from the cache.
        FractionProgress bar("phantom '" + src.phantom + "'", quiet);
        scene = phantom::load_or_make_phantom(src.phantom, bar.callback());
        bar.finish(std::to_string(scene.lines.line_count()) + " lines");
        io::apply_units_option(scene.lines.units, src.units);
    } else {
        io::LoadOptions o;
        o.time_array = src.time_array;
        o.velocity_array = src.velocity_array;
        o.time_step = src.time_step;
        o.units = src.units;
        o.streamlines = src.streamlines;
        o.pseudo_time = src.pseudo_time;
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
    if (!quiet) {
        const Units& u = scene.lines.units;
        std::fprintf(stderr, "data: %s — %zu lines, %zu points, t %.2f..%.2f%s%s, speed %.3g..%.3g%s%s%s\n",
                     scene.source.c_str(), scene.lines.line_count(), scene.lines.point_count(), scene.lines.time_min(),
                     scene.lines.time_max(), u.time.empty() ? "" : " ", u.time.c_str(), scene.lines.speed_min(),
                     scene.lines.speed_max(), u.velocity.empty() ? "" : " ", u.velocity.c_str(),
                     scene.mesh ? (", wall " + std::to_string(scene.mesh->index.size() / 3) + " triangles").c_str() : "");
    }
    return scene;
}

}  // namespace pathlet::cli
