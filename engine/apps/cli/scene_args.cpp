#include "scene_args.hpp"

#include "args.hpp"
#include "renderer.hpp"

#include "fraction_progress.hpp"
#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
#include "io/units.hpp"
#include "phantom/phantom.hpp"
#include "util/text.hpp"
#include <pathlet/text.hpp>

#include <algorithm>
#include <cstdio>

namespace pathlet::cli {

Scene load_scene(const SceneSource& src, bool quiet) {
    Scene scene;
    if (src.data.empty()) {
        // Generated once (tracing takes a while on two cores), then read from the cache.
        FractionProgress bar("phantom '" + src.phantom + "'", quiet);
        scene = phantom::load_or_make_phantom(src.phantom, bar.callback());
        bar.finish(std::to_string(scene.lines.line_count()) + " lines");
        io::apply_units_option(scene.lines.units, src.load.units);
    } else {
        io::LoadReport rep;
        scene.lines = io::load_pathlines(src.data, src.load, &rep);
        scene.source = src.data;
        // Nothing to draw is an error, not a blank picture (pathlet info still shows the numbers).
        if (scene.lines.line_count() == 0) {
            std::vector<std::string> dropped;
            for (const auto& w : rep.warnings)
                if (w.rfind("dropped", 0) == 0) dropped.push_back(w);
            throw DataError(src.data + ": no line to draw after repair (" +
                                (dropped.empty() ? std::string("the file holds no lines") : text::join(dropped, "; ")) +
                                "); 'pathlet info " + text::shell_quote(src.data) + "' shows what it holds");
        }
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

void check_time_in_data(const TimeRange& t, const std::string& given, const Scene& scene, bool allow_empty) {
    if (allow_empty || scene.lines.timeless) return;
    const double t0 = scene.lines.time_min(), t1 = scene.lines.time_max();
    const double slack = 1e-6 * std::max(1.0, t1 - t0);
    const std::vector<double> times = t.times();
    const double first = times.front(), last = times.back();
    if (first >= t0 - slack && last <= t1 + slack) return;
    char span[160];
    std::snprintf(span, sizeof span, "%g..%g s", t0, t1);
    const std::string what = times.size() == 1 ? "is outside" : "reaches outside";
    throw InputError("--time " + given + " " + what + " the data's time span, " + span + " (" + scene.source +
                     "): its frames would be empty; give a time within " + span +
                     ", or --allow-empty-frames to render them anyway");
}

}  // namespace pathlet::cli
