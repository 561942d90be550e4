#include "common/scene_source.hpp"

#include "common/data_bundles.hpp"
#include "common/fraction_progress.hpp"
#include "io/file_bytes.hpp"
#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
#include "io/units.hpp"
#include "phantom/phantom.hpp"
#include "util/text.hpp"
#include <pathlet/text.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>

namespace pathlet {

namespace {

// The repair's note that a file holds streamlines: one line for all bundles, not one a file.
bool streamlines_note(const std::string& warning) { return warning.rfind("no time and no velocity", 0) == 0; }

// One file, repaired; its warnings on stderr (but the streamlines note, for a bundle). Nothing
// to draw is an error, not a blank picture (pathlet info still shows the numbers).
Pathlines load_one(const std::string& file, const io::LoadOptions& opts, bool bundle = false) {
    io::LoadReport rep;
    Pathlines lines = io::load_pathlines(file, opts, &rep);
    if (lines.line_count() == 0) {
        std::vector<std::string> dropped;
        for (const auto& w : rep.warnings)
            if (w.rfind("dropped", 0) == 0) dropped.push_back(w);
        throw DataError(file + ": no line to draw after repair (" +
                        (dropped.empty() ? std::string("the file holds no lines") : text::join(dropped, "; ")) +
                        "); 'pathlet info " + text::shell_quote(file) + "' shows what it holds");
    }
    for (const auto& w : rep.warnings)
        if (!(bundle && streamlines_note(w))) std::fprintf(stderr, "warning: %s: %s\n", file.c_str(), w.c_str());
    return lines;
}

// Several files: each loaded as it is (timeless tracts stay timeless, so kinds compare), then
// joined; --pseudo-time applies to the joined lines, at one speed for all.
Pathlines load_bundles(const std::vector<std::string>& files, const io::LoadOptions& opts) {
    io::LoadOptions each = opts;
    each.pseudo_time = false;
    each.streamlines = opts.streamlines || opts.pseudo_time;
    std::vector<LoadedBundle> parts;
    for (const std::string& f : files) parts.push_back({f, load_one(f, each, true)});
    Pathlines joined = join_bundles(std::move(parts));
    if (joined.timeless)
        std::fprintf(stderr, "note: %zu files of streamlines without time (tracts): drawn whole; --pseudo-time animates "
                             "them along their arc length\n", files.size());
    if (opts.pseudo_time && joined.timeless) {
        joined.timeless = false;
        std::fprintf(stderr, "note: --pseudo-time: the streamlines animate along their pseudo-time\n");
    }
    return joined;
}

std::string source_name(const std::vector<std::string>& given, size_t files) {
    const std::string count = " [" + std::to_string(files) + " files]";
    if (files == 1 || given.size() == 1) return given.front() + (files > 1 ? count : "");
    return given.front() + " and " + std::to_string(given.size() - 1) + " more" + count;
}

}  // namespace

Scene load_scene(const SceneSource& src, bool quiet) {
    Scene scene;
    if (src.data.empty()) {
        // Generated once (tracing takes a while on two cores), then read from the cache.
        FractionProgress bar("phantom '" + src.phantom + "'", quiet);
        scene = phantom::load_or_make_phantom(src.phantom, bar.callback());
        bar.finish(std::to_string(scene.lines.line_count()) + " lines");
        io::apply_units_option(scene.lines.units, src.load.units);
    } else {
        const std::vector<std::string> files = data_files(src.data);
        if (files.size() == 1) {
            scene.lines = load_one(files.front(), src.load);
            scene.lines.bundle_names = {bundle_name(files.front())};
        } else {
            scene.lines = load_bundles(files, src.load);
        }
        scene.source = source_name(src.data, files.size());
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
        if (scene.lines.bundle_names.size() > 1)
            std::fprintf(stderr, "bundles: %s\n", text::join(scene.lines.bundle_names).c_str());
    }
    return scene;
}

std::string default_graph(const SceneSource& src) {
    if (src.data.empty()) return "variant1_lineao";
    for (const std::string& f : data_files(src.data)) {
        std::ifstream in(f, std::ios::binary);
        std::string head(64, '\0');
        in.read(head.data(), std::streamsize(head.size()));
        head.resize(size_t(std::max<std::streamsize>(in.gcount(), 0)));
        const io::Sniffed kind = io::sniff(head, f);
        if (kind != io::Sniffed::TrackVis && kind != io::Sniffed::MrtrixTck) return "variant1_lineao";
    }
    return "tracts_lineao";
}

std::string default_graph_noted(const SceneSource& src, bool quiet) {
    const std::string g = default_graph(src);
    if (g != "variant1_lineao" && !quiet)
        std::fprintf(stderr, "graph: %s (the data are tracts: direction colours, whole lines; give a graph to choose "
                             "another)\n", g.c_str());
    return g;
}

}  // namespace pathlet
