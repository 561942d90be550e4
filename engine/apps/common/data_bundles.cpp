// Several data files as one scene: expanding folders and globs into files, and joining the
// files' lines into bundles (tractography arrives as a file per bundle).
#include "common/data_bundles.hpp"
#include "common/scene_source.hpp"

#include <pathlet/text.hpp>

#include <glob.h>

#include <algorithm>
#include <filesystem>
#include <map>

namespace pathlet {

namespace fs = std::filesystem;

const std::vector<std::string>& data_file_extensions() {
    static const std::vector<std::string> ext{".trk", ".tck", ".vtk", ".vtp", ".pathlet", ".txt"};
    return ext;
}

namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

bool is_data_file(const fs::directory_entry& e) {
    if (!e.is_regular_file()) return false;
    const auto& ext = data_file_extensions();
    return std::find(ext.begin(), ext.end(), lower(e.path().extension().string())) != ext.end();
}

std::vector<std::string> folder_files(const std::string& dir) {
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(dir))
        if (is_data_file(e)) files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    if (files.empty())
        throw DataChoiceError(dir + ": a folder with no data files (looked for " + text::join(data_file_extensions()) +
                              "); give files, or a folder that holds them");
    return files;
}

std::vector<std::string> glob_files(const std::string& pattern) {
    glob_t g{};
    const int rc = ::glob(pattern.c_str(), 0, nullptr, &g);
    std::vector<std::string> files;
    if (rc == 0)
        for (size_t i = 0; i < g.gl_pathc; ++i)
            if (fs::is_regular_file(g.gl_pathv[i])) files.push_back(g.gl_pathv[i]);
    globfree(&g);
    if (files.empty()) throw DataChoiceError(pattern + ": the pattern matches no file");
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace

std::vector<std::string> data_files(const std::vector<std::string>& given) {
    std::vector<std::string> files;
    for (const std::string& g : given) {
        std::vector<std::string> some;
        if (fs::is_directory(g)) some = folder_files(g);
        else if (!fs::exists(g) && g.find_first_of("*?[") != std::string::npos) some = glob_files(g);
        else if (!fs::exists(g) && (fs::path(g).extension() == ".json" || !fs::path(g).has_extension()))
            throw DataChoiceError(g + ": no such data file; it looks like a graph: --data takes every argument up to "
                                      "the next option, so give the graph before it (pathlet render GRAPH --data FILE...)");
        else some = {g};  // a file that is not there is the loader's error, with its name
        files.insert(files.end(), some.begin(), some.end());
    }
    // Each file is a bundle named after its stem: two of one stem would share a name.
    std::map<std::string, std::string> by_stem;
    for (const std::string& f : files) {
        const std::string stem = fs::path(f).stem().string();
        auto [it, fresh] = by_stem.emplace(stem, f);
        if (!fresh)
            throw DataChoiceError(it->second + " and " + f + ": two data files named '" + stem +
                                  "' (each file is a bundle named after its file; rename one, or give each once)");
    }
    return files;
}

namespace {

// Each file's pseudo-time runs at 10 % of its own diagonal per second; joined, every bundle
// runs at 10 % of the joined diagonal, as one file holding them all would (pathline_repair).
void share_pseudo_time(Pathlines& joined) {
    const Bounds b = joined.bounds();
    const double diag = b.valid() ? double(glm::length(b.hi - b.lo)) : 0.0;
    const double speed = diag > 0.0 ? 0.1 * diag : 1.0;
    for (size_t li = 0; li < joined.lines.size(); ++li) {
        const LineRange r = joined.lines[li];
        // A timeless line's velocity is its unit tangent at its file's pseudo-speed.
        const double own = r.count ? double(glm::length(joined.velocity[r.first])) : 0.0;
        if (!(own > 0.0)) continue;
        const float time_scale = float(own / speed), speed_scale = float(speed / own);
        for (uint32_t k = r.first; k < r.first + r.count; ++k) {
            joined.time[k] *= time_scale;
            joined.velocity[k] *= speed_scale;
        }
    }
}

}  // namespace

std::string bundle_name(const std::string& file) { return fs::path(file).stem().string(); }

Pathlines join_bundles(std::vector<LoadedBundle> parts) {
    std::sort(parts.begin(), parts.end(),
              [](const LoadedBundle& a, const LoadedBundle& b) { return bundle_name(a.file) < bundle_name(b.file); });
    for (const LoadedBundle& p : parts)
        if (p.lines.timeless != parts.front().lines.timeless) {
            const LoadedBundle& timed = p.lines.timeless ? parts.front() : p;
            const LoadedBundle& timeless = p.lines.timeless ? p : parts.front();
            throw DataChoiceError("files of mixed kinds: " + timed.file + " has time (pathlines), " + timeless.file +
                                  " has none (tracts or streamlines); give files of one kind");
        }
    Pathlines out;
    out.units = parts.front().lines.units;
    out.timeless = parts.front().lines.timeless;
    // Point arrays every file has, by name, stay; others would leave holes.
    for (const PointArray& a : parts.front().lines.arrays) {
        bool everywhere = true;
        for (const LoadedBundle& p : parts) everywhere = everywhere && p.lines.array(a.name);
        if (everywhere) out.arrays.push_back({a.name, {}});
    }
    for (uint32_t b = 0; b < uint32_t(parts.size()); ++b) {
        const Pathlines& pl = parts[b].lines;
        out.bundle_names.push_back(bundle_name(parts[b].file));
        const uint32_t base = uint32_t(out.position.size());
        for (LineRange r : pl.lines) {
            r.first += base;
            out.lines.push_back(r);
            out.line_bundle.push_back(b);
        }
        out.position.insert(out.position.end(), pl.position.begin(), pl.position.end());
        out.time.insert(out.time.end(), pl.time.begin(), pl.time.end());
        out.velocity.insert(out.velocity.end(), pl.velocity.begin(), pl.velocity.end());
        for (PointArray& a : out.arrays) {
            const std::vector<float>& v = pl.array(a.name)->values;
            a.values.insert(a.values.end(), v.begin(), v.end());
        }
    }
    if (out.timeless) share_pseudo_time(out);
    return out;
}

}  // namespace pathlet
