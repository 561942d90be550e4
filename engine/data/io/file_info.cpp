#include "file_info.hpp"

#include "file_bytes.hpp"
#include "mesh_io.hpp"
#include "units.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace pathlet::io {

namespace {

std::string fmt(const char* f, auto... a) {
    char buf[512];
    std::snprintf(buf, sizeof buf, f, a...);
    return buf;
}

std::string bounds_text(const Bounds& b) {
    if (!b.valid()) return "(none)";
    return fmt("x %.6g .. %.6g, y %.6g .. %.6g, z %.6g .. %.6g", b.lo.x, b.hi.x, b.lo.y, b.hi.y, b.lo.z, b.hi.z);
}

// Sniffs the whole file (binary STL is recognised by its total size).
bool is_mesh(const std::string& path) {
    Sniffed s = sniff(read_file_bytes(path), path);
    return s == Sniffed::StlAscii || s == Sniffed::StlBinary || s == Sniffed::Obj || s == Sniffed::Gltf || s == Sniffed::Glb;
}

void common(std::ostringstream& o, const LoadReport& r) {
    o << "warnings:  " << (r.warnings.empty() ? "none" : "") << "\n";
    for (auto& w : r.warnings) o << "  - " << w << "\n";
}

}  // namespace

std::string describe_file(const std::string& path) { return describe_file(path, {}); }

std::string describe_file(const std::string& path, const LoadOptions& opts, const DescribeMore& more) {
    std::ostringstream o;
    LoadReport r;
    o << "file:      " << path << "\n";
    if (is_mesh(path)) {
        Mesh m = load_mesh(path, &r);
        o << "format:    " << r.format << "\n";
        o << "kind:      triangle mesh\n";
        o << "vertices:  " << m.position.size() << "\n";
        o << "triangles: " << m.index.size() / 3 << "\n";
        o << "bounds:    " << bounds_text(m.bounds()) << "\n";
        common(o, r);
        return o.str();
    }
    Pathlines p = load_pathlines(path, opts, &r);
    o << "format:    " << r.format << "\n";
    return o.str() + describe_pathlines(p, r, more);
}

std::string describe_pathlines(const Pathlines& p, const LoadReport& r, const DescribeMore& more) {
    std::ostringstream o;
    o << "kind:      pathlines\n";
    o << "lines:     " << p.line_count() << "\n";
    o << "points:    " << p.point_count() << "\n";
    o << "arrays:    ";
    for (size_t i = 0; i < r.arrays.size(); ++i) o << (i ? ", " : "") << r.arrays[i];
    o << (r.arrays.empty() ? "none" : "") << "\n";
    const Units& u = p.units;
    const bool missing = u.length.empty() || (!p.timeless && u.velocity.empty());
    o << "units:     " << describe_units(u) << (missing ? " (the file does not say them all: --units LENGTH[,VELOCITY])" : "")
      << "\n";
    if (p.timeless) o << "time:      none (streamlines: drawn whole; --pseudo-time animates them along the arc length)\n";
    if (!p.empty() && !p.timeless) {
        const std::string ts = u.time.empty() ? "" : " " + u.time;
        o << fmt("time:      %.6g .. %.6g%s (span %.6g%s)\n", p.time_min(), p.time_max(), ts.c_str(), p.time_max() - p.time_min(),
                 ts.c_str());
        o << fmt("speed:     %.6g .. %.6g%s\n", p.speed_min(), p.speed_max(), u.velocity.empty() ? "" : (" " + u.velocity).c_str());
    }
    if (!p.empty()) {
        o << "bounds:    " << bounds_text(p.bounds()) << (u.length.empty() ? "" : " (" + u.length + ")") << "\n";
        std::vector<uint32_t> counts;
        for (auto& l : p.lines) counts.push_back(l.count);
        std::sort(counts.begin(), counts.end());
        o << "points per line: min " << counts.front() << ", median " << counts[counts.size() / 2] << ", max " << counts.back()
          << "\n";
    }
    if (more) o << more(p);
    common(o, r);
    return o.str();
}

}  // namespace pathlet::io
