#include "util/input_limits.hpp"
#include "units.hpp"
#include "raw_polylines.hpp"

#include "byte_reader.hpp"
#include "util/text.hpp"
#include <pathlet/text.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace pathlet::io {

void append_piece(RawPolylines& dst, RawPolylines&& piece, LoadReport& report) {
    const int64_t base_point = int64_t(dst.point_count());
    const int64_t base_conn = int64_t(dst.connectivity.size());
    const bool first = dst.points.empty() && dst.line_count() == 0 && dst.point_arrays.empty();
    dst.points.insert(dst.points.end(), piece.points.begin(), piece.points.end());
    for (size_t i = 1; i < piece.offsets.size(); ++i) dst.offsets.push_back(piece.offsets[i] + base_conn);
    for (auto c : piece.connectivity) dst.connectivity.push_back(c < 0 ? c : c + base_point);
    dst.polygons += piece.polygons;
    if (first) {
        dst.point_arrays = std::move(piece.point_arrays);
        dst.where_lines = piece.where_lines;
        dst.where_data = piece.where_data;
        return;
    }
    std::vector<RawArray> kept;
    for (auto& a : dst.point_arrays) {
        auto it = std::find_if(piece.point_arrays.begin(), piece.point_arrays.end(),
                               [&](const RawArray& b) { return b.name == a.name && b.components == a.components; });
        if (it == piece.point_arrays.end()) {
            report.warnings.push_back("dropped point array '" + a.name + "': missing from a later piece");
            continue;
        }
        a.values.insert(a.values.end(), it->values.begin(), it->values.end());
        kept.push_back(std::move(a));
    }
    dst.point_arrays = std::move(kept);
}

void validate_topology(const RawPolylines& raw, const std::string& file) {
    const auto& off = raw.offsets;
    if (off.empty() || off.front() != 0)
        fail_at(file, raw.where_lines, "line offsets must start at 0 (got " + std::to_string(off.empty() ? -1 : off.front()) + ")");
    for (size_t i = 1; i < off.size(); ++i)
        if (off[i] < off[i - 1])
            fail_at(file, raw.where_lines, "line offsets are not monotone: offset " + std::to_string(i) + " is " +
                                               std::to_string(off[i]) + " after " + std::to_string(off[i - 1]));
    if (uint64_t(off.back()) != raw.connectivity.size())
        fail_at(file, raw.where_lines, "line offsets end at " + std::to_string(off.back()) + " but the connectivity has " +
                                           std::to_string(raw.connectivity.size()) + " entries");
    const int64_t n = int64_t(raw.point_count());
    for (size_t i = 0; i < raw.connectivity.size(); ++i) {
        int64_t c = raw.connectivity[i];
        if (c < 0 || c >= n)
            fail_at(file, raw.where_lines, "line connectivity entry " + std::to_string(i) + " is point index " +
                                               std::to_string(c) + ", but there are only " + std::to_string(n) + " points");
    }
    for (auto& a : raw.point_arrays)
        if (a.values.size() != raw.point_count() * size_t(a.components))
            fail_at(file, raw.where_data, "point array '" + a.name + "' has " + std::to_string(a.values.size() / std::max(a.components, 1)) +
                                              " tuples but there are " + std::to_string(raw.point_count()) + " points");
}

static const RawArray* pick(const std::vector<RawArray>& arrays, const std::string& wanted,
                            std::initializer_list<const char*> automatic, int comps, const char* role,
                            const char* option, const std::string& file, const std::string& where) {
    if (!wanted.empty()) {
        for (auto& a : arrays)
            if (a.name == wanted || iequals(a.name, wanted)) {
                if (a.components != comps)
                    fail_at(file, where, std::string(role) + " array '" + a.name + "' has " + std::to_string(a.components) +
                                             " components, expected " + std::to_string(comps));
                return &a;
            }
        std::vector<std::string> names;
        for (auto& a : arrays) names.push_back(a.name);
        fail_at(file, where, std::string("no point array named '") + wanted + "'" + text::did_you_mean(wanted, names) + " (" +
                                 option + "); arrays present: " + (names.empty() ? "none" : text::join(names)));
    }
    for (const char* name : automatic)
        for (auto& a : arrays)
            if (iequals(a.name, name) && a.components == comps) return &a;
    return nullptr;
}

Pathlines assemble_pathlines(RawPolylines&& raw, const LoadOptions& opts, LoadReport& report, const std::string& file) {
    validate_topology(raw, file);
    for (auto& a : raw.point_arrays)
        report.arrays.push_back(a.name + " (" + std::to_string(a.components) + " comp)");
    Pathlines out;
    if (raw.line_count() == 0) {
        if (raw.polygons > 0)
            fail_at(file, raw.where_lines, "holds " + std::to_string(raw.polygons) +
                                               " polygons and no lines: this is a surface, not pathlines; load it as a mesh "
                                               "(e.g. export STL/OBJ/glTF)");
        report.warnings.push_back("the file holds no lines: empty pathline set");
        return out;
    }
    const RawArray* t = pick(raw.point_arrays, opts.time_array, {"time", "t", "integrationtime"}, 1, "time",
                             "--time-array; time_array= in Python", file, raw.where_data);
    const RawArray* v = pick(raw.point_arrays, opts.velocity_array, {"velocity", "vel", "u", "v"}, 3, "velocity",
                             "--velocity-array; velocity_array= in Python", file, raw.where_data);
    if (!t && !v && !opts.streamlines && !opts.pseudo_time) {
        std::string names;
        for (auto& s : report.arrays) names += (names.empty() ? "" : ", ") + s;
        fail_at(file, raw.where_data,
                "no time array and no velocity array, so pathline time cannot be derived. Point arrays present: " +
                    (names.empty() ? std::string("none") : names) +
                    ". Name the time array with --time-array NAME or the velocity with --velocity-array NAME (in Python: "
                    "time_array=, velocity_array=); streamlines without either load with --streamlines (drawn whole) or "
                    "--pseudo-time (animated along the arc length)");
    }
    const size_t total = raw.connectivity.size();
    out.position.resize(total);
    if (t) out.time.resize(total);
    if (v) out.velocity.resize(total);
    out.lines.reserve(raw.line_count());
    const float* P = raw.points.data();
    for (size_t k = 0; k < total; ++k) {
        size_t i = size_t(raw.connectivity[k]);
        out.position[k] = {P[3 * i], P[3 * i + 1], P[3 * i + 2]};
        if (t) out.time[k] = t->values[i];
        if (v) out.velocity[k] = {v->values[3 * i], v->values[3 * i + 1], v->values[3 * i + 2]};
    }
    // The other point arrays travel with their points (a vector as its magnitude).
    for (const RawArray& a : raw.point_arrays) {
        if (&a == t || &a == v || a.components < 1) continue;
        PointArray pa{a.name, std::vector<float>(total)};
        const size_t c = size_t(a.components);
        for (size_t k = 0; k < total; ++k) {
            const float* x = &a.values[size_t(raw.connectivity[k]) * c];
            double m = 0.0;
            for (size_t j = 0; j < c; ++j) m += double(x[j]) * double(x[j]);
            pa.values[k] = c == 1 ? x[0] : float(std::sqrt(m));
        }
        out.arrays.push_back(std::move(pa));
    }
    for (size_t l = 0; l + 1 < raw.offsets.size(); ++l)
        out.lines.push_back({uint32_t(raw.offsets[l]), uint32_t(raw.offsets[l + 1] - raw.offsets[l])});
    out.units = raw.units;
    repair_pathlines(out, report, file);
    return out;
}

namespace {

bool finite3(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// A position the data set can keep: finite and within io::max_coordinate(). One huge but
// finite outlier (3e38) would otherwise overflow the diagonal to inf and make every other
// point look like a duplicate of its neighbour.
bool usable(const glm::vec3& p) {
    const double m = io::max_coordinate();
    return finite3(p) && std::abs(p.x) <= m && std::abs(p.y) <= m && std::abs(p.z) <= m;
}

std::string short_number(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}

struct Counts {
    size_t nonfinite_points = 0, nonfinite_lines = 0, split_extra = 0, outlier_points = 0;
    size_t dup_points = 0, dup_lines = 0, equal_time_points = 0;
    size_t short_lines = 0, short_points = 0, reversed = 0, sorted = 0;
};

// Fast path: nothing to repair (the common case for our own caches and clean exports).
bool is_clean(const Pathlines& pl, float eps2) {
    const bool ht = !pl.time.empty(), hv = !pl.velocity.empty();
    if (!ht || !hv) return false;
    uint64_t expect = 0;
    for (auto& r : pl.lines) {
        if (r.first != expect || r.count < 2) return false;
        expect += r.count;
        for (uint32_t k = r.first; k < r.first + r.count; ++k) {
            if (!usable(pl.position[k]) || !std::isfinite(pl.time[k]) || !finite3(pl.velocity[k])) return false;
            if (k > r.first) {
                glm::vec3 d = pl.position[k] - pl.position[k - 1];
                if (glm::dot(d, d) <= eps2 || !(pl.time[k] > pl.time[k - 1])) return false;
            }
        }
    }
    return expect == pl.position.size();
}

}  // namespace

void repair_pathlines(Pathlines& pl, LoadReport& report, const std::string& file) {
    if (pl.lines.empty()) {  // nothing drawable; callers have already warned
        pl = Pathlines{};
        return;
    }
    const bool has_time = !pl.time.empty(), has_vel = !pl.velocity.empty();
    if ((has_time && pl.time.size() != pl.position.size()) || (has_vel && pl.velocity.size() != pl.position.size()))
        fail_at(file, "byte 0", "time/velocity sizes disagree with the point count");
    for (const PointArray& a : pl.arrays)
        if (a.values.size() != pl.position.size())
            fail_at(file, "byte 0", "point array '" + a.name + "' size disagrees with the point count");
    for (auto& r : pl.lines)
        if (uint64_t(r.first) + r.count > pl.position.size())
            fail_at(file, "byte 0", "line range beyond the point count");

    // Zero-length threshold relative to the data extent: a millionth of the diagonal.
    // Over usable points only, in double: outliers are dropped below, not measured.
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const auto& p : pl.position)
        if (usable(p)) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
    double diag = hi.x >= lo.x ? glm::length(hi - lo) : 0.0;
    float eps = float(1e-6 * diag);
    float eps2 = eps * eps;
    if (is_clean(pl, eps2)) return;

    Counts c;
    Pathlines out;
    for (const PointArray& a : pl.arrays) out.arrays.push_back({a.name, {}});
    out.position.reserve(pl.position.size());
    if (has_time) out.time.reserve(pl.time.size());
    if (has_vel) out.velocity.reserve(pl.velocity.size());
    std::vector<uint32_t> seg;

    auto flush = [&](bool& line_had_dup) {
        if (has_time && seg.size() > 1) {
            bool inc = true, dec = true;
            for (size_t i = 1; i < seg.size(); ++i) {
                if (pl.time[seg[i]] < pl.time[seg[i - 1]]) inc = false;
                if (pl.time[seg[i]] > pl.time[seg[i - 1]]) dec = false;
            }
            if (!inc && dec) { std::reverse(seg.begin(), seg.end()); ++c.reversed; }
            else if (!inc) {
                std::stable_sort(seg.begin(), seg.end(), [&](uint32_t a, uint32_t b2) { return pl.time[a] < pl.time[b2]; });
                ++c.sorted;
            }
        }
        size_t first = out.position.size();
        for (size_t i = 0; i < seg.size(); ++i) {
            uint32_t k = seg[i];
            if (out.position.size() > first) {
                size_t last = out.position.size() - 1;
                glm::vec3 d = pl.position[k] - out.position[last];
                if (glm::dot(d, d) <= eps2) { ++c.dup_points; line_had_dup = true; continue; }
                if (has_time && !(pl.time[k] > out.time[last])) { ++c.equal_time_points; continue; }
            }
            out.position.push_back(pl.position[k]);
            if (has_time) out.time.push_back(pl.time[k]);
            if (has_vel) out.velocity.push_back(pl.velocity[k]);
            for (size_t a = 0; a < pl.arrays.size(); ++a) out.arrays[a].values.push_back(pl.arrays[a].values[k]);
        }
        size_t n = out.position.size() - first;
        if (n < 2) {
            if (!seg.empty()) { ++c.short_lines; c.short_points += n; }
            out.position.resize(first);
            if (has_time) out.time.resize(first);
            if (has_vel) out.velocity.resize(first);
            for (PointArray& a : out.arrays) a.values.resize(first);
        } else {
            out.lines.push_back({uint32_t(first), uint32_t(n)});
        }
        seg.clear();
    };

    for (auto& r : pl.lines) {
        bool had_bad = false, had_dup = false;
        size_t pieces = 0;
        for (uint32_t k = r.first; k < r.first + r.count; ++k) {
            bool ok = usable(pl.position[k]) && (!has_time || std::isfinite(pl.time[k])) && (!has_vel || finite3(pl.velocity[k]));
            if (ok) { seg.push_back(k); continue; }
            if (finite3(pl.position[k]) && !usable(pl.position[k])) ++c.outlier_points;  // dropped alike, said apart
            else ++c.nonfinite_points;
            had_bad = true;
            if (!seg.empty()) { flush(had_dup); ++pieces; }
        }
        if (!seg.empty()) { flush(had_dup); ++pieces; }
        else if (r.count < 2 && !had_bad) { ++c.short_lines; c.short_points += r.count; }
        if (had_bad) { ++c.nonfinite_lines; if (pieces > 1) c.split_extra += pieces - 1; }
        if (had_dup) ++c.dup_lines;
    }

    auto& w = report.warnings;
    if (c.nonfinite_points)
        w.push_back("dropped " + std::to_string(c.nonfinite_points) + " non-finite (NaN/inf) points in " +
                    std::to_string(c.nonfinite_lines) + " lines" +
                    (c.split_extra ? " (split into " + std::to_string(c.split_extra) + " extra lines)" : ""));
    if (c.outlier_points)
        w.push_back("dropped " + std::to_string(c.outlier_points) + " outlying points (a coordinate beyond +-" +
                    short_number(io::max_coordinate()) + "; PATHLET_MAX_COORDINATE raises the limit)");
    if (c.dup_points)
        w.push_back("dropped " + std::to_string(c.dup_points) + " duplicate consecutive points (zero-length segments) in " +
                    std::to_string(c.dup_lines) + " lines");
    if (c.equal_time_points)
        w.push_back("dropped " + std::to_string(c.equal_time_points) + " points whose time repeats the previous point's");
    if (c.reversed) w.push_back("reversed " + std::to_string(c.reversed) + " lines whose time decreased along the line");
    if (c.sorted) w.push_back("sorted " + std::to_string(c.sorted) + " lines by time (time was not monotonic)");
    if (c.short_lines)
        w.push_back("dropped " + std::to_string(c.short_lines) + " lines with fewer than 2 distinct points");

    out.units = pl.units;
    if (!has_time && !has_vel) {
        // Streamlines (tractography, centrelines): a pseudo-time along the arc length at 10 % of
        // the data's diagonal per second, so a 1 s window shows a tenth of the diagonal moving
        // along each line whatever the data's scale. Time and speed mean nothing physical.
        const double pseudo_speed = diag > 0.0 ? 0.1 * diag : 1.0;
        out.time.resize(out.position.size());
        for (auto& r : out.lines) {
            double arc = 0.0;
            out.time[r.first] = 0.0f;
            for (uint32_t k = r.first + 1; k < r.first + r.count; ++k) {
                arc += glm::length(glm::dvec3(out.position[k]) - glm::dvec3(out.position[k - 1]));
                out.time[k] = std::max(float(arc / pseudo_speed), std::nextafter(out.time[k - 1], INFINITY));
            }
        }
        // Velocity: the unit tangent at exactly the pseudo-speed, so a speed colour map gives
        // every streamline the same colour instead of noise from uneven point spacing.
        out.velocity.resize(out.position.size());
        for (auto& r : out.lines) {
            const uint32_t a = r.first, e = r.first + r.count - 1;
            for (uint32_t k = a; k <= e; ++k) {
                const glm::vec3 d = out.position[k == e ? e : k + 1] - out.position[k == a ? a : k - 1];
                const float len = glm::length(d);
                out.velocity[k] = len > 0.0f ? d * float(pseudo_speed / len) : glm::vec3(float(pseudo_speed), 0.0f, 0.0f);
            }
        }
        out.units.time = out.units.velocity = "";
        out.timeless = true;
        w.push_back("no time and no velocity: streamlines, drawn whole (pseudo-time along the arc length for "
                    "animation: " + short_number(pseudo_speed) + " length units per second, 10 % of the diagonal)");
    } else if (!has_time) {
        // Time from arc length / speed: dt = |dp| / mean(|v_k|, |v_k+1|). A stagnant pair
        // (both speeds 0) uses the median speed of the whole set so time stays increasing.
        std::vector<float> speeds;
        speeds.reserve(out.velocity.size());
        for (auto& v : out.velocity) if (glm::length(v) > 0) speeds.push_back(glm::length(v));
        float fallback = 1.0f;
        if (!speeds.empty()) {
            std::nth_element(speeds.begin(), speeds.begin() + speeds.size() / 2, speeds.end());
            fallback = speeds[speeds.size() / 2];
        }
        out.time.resize(out.position.size());
        for (auto& r : out.lines) {
            double t = 0.0;
            out.time[r.first] = 0.0f;
            for (uint32_t k = r.first + 1; k < r.first + r.count; ++k) {
                float s = 0.5f * (glm::length(out.velocity[k]) + glm::length(out.velocity[k - 1]));
                if (!(s > 0)) s = fallback;
                t += glm::length(out.position[k] - out.position[k - 1]) / s;
                out.time[k] = float(t);
                if (!(out.time[k] > out.time[k - 1])) out.time[k] = std::nextafter(out.time[k - 1], INFINITY);
            }
        }
        w.push_back("no time array: derived time from arc length / speed (each line starts at t = 0)");
        // mm over mm/s is s; any other pairing leaves the time unit unknown.
        const std::string per_s = out.units.length.empty() ? "" : out.units.length + "/s";
        out.units.time = !per_s.empty() && out.units.velocity == per_s ? "s" : "";
    }
    if (!has_vel && !out.timeless) {
        // Central differences inside a line, one-sided at its ends.
        out.velocity.resize(out.position.size());
        for (auto& r : out.lines) {
            uint32_t a = r.first, e = r.first + r.count - 1;
            for (uint32_t k = a; k <= e; ++k) {
                uint32_t i0 = k == a ? a : k - 1, i1 = k == e ? e : k + 1;
                out.velocity[k] = (out.position[i1] - out.position[i0]) / (out.time[i1] - out.time[i0]);
            }
        }
        if (has_time) {
            w.push_back("no velocity array: derived velocity by finite differences of position over time");
            if (out.units.velocity.empty()) out.units.velocity = derived_velocity_unit(out.units);
        }
    }
    if (out.lines.empty() && !pl.lines.empty()) w.push_back("no drawable lines remain after repair: empty pathline set");
    pl = std::move(out);
}

}  // namespace pathlet::io
