#include "common/scene_source.hpp"

#include "common/fraction_progress.hpp"
#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
#include "io/units.hpp"
#include "phantom/phantom.hpp"
#include "util/text.hpp"
#include <pathlet/text.hpp>

#include <cstdio>

namespace pathlet {

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

}  // namespace pathlet
