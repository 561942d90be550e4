// Disk cache of generated phantoms: generation takes seconds, loading milliseconds.
#include "phantom.hpp"

#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
#include "util/cache_dir.hpp"

#include <cstdlib>
#include <filesystem>

namespace pathlet::phantom {

// Bump when the generator's output changes, so stale caches are never reused.
static constexpr const char* kPhantomVersion = "v2";  // v2: no points of one float time

std::string phantom_cache_path(const std::string& spec) {
    const PhantomOptions o = phantom_preset(spec);  // validates the name
    const std::string density = o.trace.density > 1 ? "-density" + std::to_string(o.trace.density) : "";
    const std::filesystem::path dir = cache_dir();
    return (dir / ("phantom-" + o.preset + density + "-" + kPhantomVersion + ".pathlet")).string();
}

Scene load_or_make_phantom(const std::string& spec, const trace::Progress& progress) {
    const std::string path = phantom_cache_path(spec);
    const std::string wall = std::filesystem::path(path).replace_extension(".glb").string();
    std::error_code ec;
    if (std::filesystem::exists(path, ec) && std::filesystem::exists(wall, ec)) {
        try {
            Scene s;
            s.lines = io::load_pathlines(path);
            s.lines.units = {"mm", "s", "mm/s"};  // caches written before units carried none
            s.mesh = io::load_mesh(wall);
            s.source = path;
            return s;
        } catch (const DataError&) {
            // A damaged cache is regenerated below.
        }
    }
    Scene s = make_phantom(phantom_preset(spec), progress);
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    // Wall first: the pathline file appearing last marks the pair complete.
    if (s.mesh) io::save_mesh(*s.mesh, wall);
    io::save_pathlines(s.lines, path, io::PathlineFormat::Native);
    return s;
}

}  // namespace pathlet::phantom
