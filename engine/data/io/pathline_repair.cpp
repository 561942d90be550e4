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

// The unit of a time derived from length over speed: mm over mm/s is s; any other pairing
// leaves it unknown.
std::string derived_time_unit(const Units& u) {
    if (u.length.empty() || u.velocity != u.length + "/s") return "";
    return "s";
}

// What the repair dropped, reordered or split, for the report's warnings.
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

// One repair of a pathline set, in stage order: check the sizes, measure the data's extent,
// keep each line's usable, distinct, time-ordered points (the pieces of a line between dropped
// points become lines of their own), say what was dropped, then derive what the file lacks:
// time (streamlines: along the arc length; else from the speed) and velocity.
class Repair {
public:
    Repair(Pathlines& pl, LoadReport& report, const std::string& file)
        : pl_(pl), warnings_(report.warnings), file_(file), has_time_(!pl.time.empty()), has_vel_(!pl.velocity.empty()) {}

    void run() {
        if (pl_.lines.empty()) {  // nothing drawable; callers have already warned
            pl_ = Pathlines{};
            return;
        }
        check_sizes();
        measure_extent();
        if (is_clean(pl_, eps2_)) return;
        start_output();
        for (const LineRange& r : pl_.lines) keep_usable_pieces(r);
        report_drops();
        out_.units = pl_.units;
        if (!has_time_ && !has_vel_) {
            pseudo_time_along_arc();
            tangent_velocity();
        } else if (!has_time_) {
            time_from_speed();
        }
        if (!has_vel_ && !out_.timeless) velocity_from_differences();
        if (out_.lines.empty()) warnings_.push_back("no drawable lines remain after repair: empty pathline set");
        pl_ = std::move(out_);
    }

private:
    void check_sizes() const {
        if ((has_time_ && pl_.time.size() != pl_.position.size()) || (has_vel_ && pl_.velocity.size() != pl_.position.size()))
            fail_at(file_, "byte 0", "time/velocity sizes disagree with the point count");
        for (const PointArray& a : pl_.arrays)
            if (a.values.size() != pl_.position.size())
                fail_at(file_, "byte 0", "point array '" + a.name + "' size disagrees with the point count");
        for (auto& r : pl_.lines)
            if (uint64_t(r.first) + r.count > pl_.position.size())
                fail_at(file_, "byte 0", "line range beyond the point count");
    }

    // Zero-length threshold relative to the data extent: a millionth of the diagonal.
    // Over usable points only, in double: outliers are dropped below, not measured.
    void measure_extent() {
        glm::dvec3 lo(1e300), hi(-1e300);
        for (const auto& p : pl_.position)
            if (usable(p)) lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p));
        diag_ = hi.x >= lo.x ? glm::length(hi - lo) : 0.0;
        const float eps = float(1e-6 * diag_);
        eps2_ = eps * eps;
    }

    void start_output() {
        for (const PointArray& a : pl_.arrays) out_.arrays.push_back({a.name, {}});
        out_.position.reserve(pl_.position.size());
        if (has_time_) out_.time.reserve(pl_.time.size());
        if (has_vel_) out_.velocity.reserve(pl_.velocity.size());
    }

    bool usable_point(uint32_t k) const {
        return usable(pl_.position[k]) && (!has_time_ || std::isfinite(pl_.time[k])) && (!has_vel_ || finite3(pl_.velocity[k]));
    }

    // One line of the input: its runs of usable points, each taken as a line of its own.
    void keep_usable_pieces(const LineRange& r) {
        bool had_bad = false, had_dup = false;
        size_t pieces = 0;
        for (uint32_t k = r.first; k < r.first + r.count; ++k) {
            if (usable_point(k)) {
                piece_.push_back(k);
                continue;
            }
            if (finite3(pl_.position[k]) && !usable(pl_.position[k])) ++c_.outlier_points;  // dropped alike, said apart
            else ++c_.nonfinite_points;
            had_bad = true;
            if (!piece_.empty()) {
                take_piece(had_dup);
                ++pieces;
            }
        }
        if (!piece_.empty()) {
            take_piece(had_dup);
            ++pieces;
        } else if (r.count < 2 && !had_bad) {
            ++c_.short_lines;
            c_.short_points += r.count;
        }
        if (had_bad) {
            ++c_.nonfinite_lines;
            if (pieces > 1) c_.split_extra += pieces - 1;
        }
        if (had_dup) ++c_.dup_lines;
    }

    // The piece in time order, its distinct points appended; a line of it when 2 or more remain.
    void take_piece(bool& line_had_dup) {
        if (has_time_ && piece_.size() > 1) order_piece_by_time();
        const size_t first = out_.position.size();
        for (uint32_t k : piece_) {
            if (out_.position.size() > first && !distinct_from_last(k, line_had_dup)) continue;
            out_.position.push_back(pl_.position[k]);
            if (has_time_) out_.time.push_back(pl_.time[k]);
            if (has_vel_) out_.velocity.push_back(pl_.velocity[k]);
            for (size_t a = 0; a < pl_.arrays.size(); ++a) out_.arrays[a].values.push_back(pl_.arrays[a].values[k]);
        }
        const size_t n = out_.position.size() - first;
        if (n < 2) {
            ++c_.short_lines;
            c_.short_points += n;
            out_.position.resize(first);
            if (has_time_) out_.time.resize(first);
            if (has_vel_) out_.velocity.resize(first);
            for (PointArray& a : out_.arrays) a.values.resize(first);
        } else {
            out_.lines.push_back({uint32_t(first), uint32_t(n)});
        }
        piece_.clear();
    }

    // A piece whose time decreases is reversed; one that goes back and forth, sorted (stable).
    void order_piece_by_time() {
        bool inc = true, dec = true;
        for (size_t i = 1; i < piece_.size(); ++i) {
            if (pl_.time[piece_[i]] < pl_.time[piece_[i - 1]]) inc = false;
            if (pl_.time[piece_[i]] > pl_.time[piece_[i - 1]]) dec = false;
        }
        if (!inc && dec) {
            std::reverse(piece_.begin(), piece_.end());
            ++c_.reversed;
        } else if (!inc) {
            std::stable_sort(piece_.begin(), piece_.end(), [&](uint32_t a, uint32_t b) { return pl_.time[a] < pl_.time[b]; });
            ++c_.sorted;
        }
    }

    // Point k against the last point kept: not at the same place, not at the same time.
    bool distinct_from_last(uint32_t k, bool& line_had_dup) {
        const size_t last = out_.position.size() - 1;
        const glm::vec3 d = pl_.position[k] - out_.position[last];
        if (glm::dot(d, d) <= eps2_) {
            ++c_.dup_points;
            line_had_dup = true;
            return false;
        }
        if (has_time_ && !(pl_.time[k] > out_.time[last])) {
            ++c_.equal_time_points;
            return false;
        }
        return true;
    }

    void report_drops() const {
        auto& w = warnings_;
        if (c_.nonfinite_points)
            w.push_back("dropped " + std::to_string(c_.nonfinite_points) + " non-finite (NaN/inf) points in " +
                        std::to_string(c_.nonfinite_lines) + " lines" +
                        (c_.split_extra ? " (split into " + std::to_string(c_.split_extra) + " extra lines)" : ""));
        if (c_.outlier_points)
            w.push_back("dropped " + std::to_string(c_.outlier_points) + " outlying points (a coordinate beyond +-" +
                        short_number(io::max_coordinate()) + "; PATHLET_MAX_COORDINATE raises the limit)");
        if (c_.dup_points)
            w.push_back("dropped " + std::to_string(c_.dup_points) + " duplicate consecutive points (zero-length segments) in " +
                        std::to_string(c_.dup_lines) + " lines");
        if (c_.equal_time_points)
            w.push_back("dropped " + std::to_string(c_.equal_time_points) + " points whose time repeats the previous point's");
        if (c_.reversed) w.push_back("reversed " + std::to_string(c_.reversed) + " lines whose time decreased along the line");
        if (c_.sorted) w.push_back("sorted " + std::to_string(c_.sorted) + " lines by time (time was not monotonic)");
        if (c_.short_lines)
            w.push_back("dropped " + std::to_string(c_.short_lines) + " lines with fewer than 2 distinct points");
    }

    // Streamlines (tractography, centrelines): a pseudo-time along the arc length at 10 % of
    // the data's diagonal per second, so a 1 s window shows a tenth of the diagonal moving
    // along each line whatever the data's scale. Time and speed mean nothing physical.
    void pseudo_time_along_arc() {
        pseudo_speed_ = diag_ > 0.0 ? 0.1 * diag_ : 1.0;
        out_.time.resize(out_.position.size());
        for (auto& r : out_.lines) {
            double arc = 0.0;
            out_.time[r.first] = 0.0f;
            for (uint32_t k = r.first + 1; k < r.first + r.count; ++k) {
                arc += glm::length(glm::dvec3(out_.position[k]) - glm::dvec3(out_.position[k - 1]));
                out_.time[k] = std::max(float(arc / pseudo_speed_), std::nextafter(out_.time[k - 1], INFINITY));
            }
        }
        out_.units.time = out_.units.velocity = "";
        out_.timeless = true;
        warnings_.push_back("no time and no velocity: streamlines, drawn whole (pseudo-time along the arc length for "
                            "animation: " + short_number(pseudo_speed_) + " length units per second, 10 % of the diagonal)");
    }

    // Velocity of streamlines: the unit tangent at exactly the pseudo-speed, so a speed colour
    // map gives every streamline the same colour instead of noise from uneven point spacing.
    void tangent_velocity() {
        out_.velocity.resize(out_.position.size());
        for (auto& r : out_.lines) {
            const uint32_t a = r.first, e = r.first + r.count - 1;
            for (uint32_t k = a; k <= e; ++k) {
                const glm::vec3 d = out_.position[k == e ? e : k + 1] - out_.position[k == a ? a : k - 1];
                const float len = glm::length(d);
                out_.velocity[k] = len > 0.0f ? d * float(pseudo_speed_ / len) : glm::vec3(float(pseudo_speed_), 0.0f, 0.0f);
            }
        }
    }

    // Time from arc length / speed: dt = |dp| / mean(|v_k|, |v_k+1|). A stagnant pair (both
    // speeds 0) uses the median speed of the whole set so time stays increasing.
    void time_from_speed() {
        std::vector<float> speeds;
        speeds.reserve(out_.velocity.size());
        for (auto& v : out_.velocity)
            if (glm::length(v) > 0) speeds.push_back(glm::length(v));
        float fallback = 1.0f;
        if (!speeds.empty()) {
            std::nth_element(speeds.begin(), speeds.begin() + speeds.size() / 2, speeds.end());
            fallback = speeds[speeds.size() / 2];
        }
        out_.time.resize(out_.position.size());
        for (auto& r : out_.lines) {
            double t = 0.0;
            out_.time[r.first] = 0.0f;
            for (uint32_t k = r.first + 1; k < r.first + r.count; ++k) {
                float s = 0.5f * (glm::length(out_.velocity[k]) + glm::length(out_.velocity[k - 1]));
                if (!(s > 0)) s = fallback;
                t += glm::length(out_.position[k] - out_.position[k - 1]) / s;
                out_.time[k] = float(t);
                if (!(out_.time[k] > out_.time[k - 1])) out_.time[k] = std::nextafter(out_.time[k - 1], INFINITY);
            }
        }
        warnings_.push_back("no time array: derived time from arc length / speed (each line starts at t = 0)");
        out_.units.time = derived_time_unit(out_.units);
    }

    // Central differences inside a line, one-sided at its ends.
    void velocity_from_differences() {
        out_.velocity.resize(out_.position.size());
        for (auto& r : out_.lines) {
            uint32_t a = r.first, e = r.first + r.count - 1;
            for (uint32_t k = a; k <= e; ++k) {
                uint32_t i0 = k == a ? a : k - 1, i1 = k == e ? e : k + 1;
                out_.velocity[k] = (out_.position[i1] - out_.position[i0]) / (out_.time[i1] - out_.time[i0]);
            }
        }
        if (has_time_) {
            warnings_.push_back("no velocity array: derived velocity by finite differences of position over time");
            if (out_.units.velocity.empty()) out_.units.velocity = derived_velocity_unit(out_.units);
        }
    }

    Pathlines& pl_;  // the input, replaced by out_ at the end
    std::vector<std::string>& warnings_;
    const std::string& file_;
    const bool has_time_, has_vel_;
    double diag_ = 0.0, pseudo_speed_ = 1.0;
    float eps2_ = 0.0f;
    Counts c_;
    Pathlines out_;
    std::vector<uint32_t> piece_;  // the input's point indices of the piece being taken
};

}  // namespace

void repair_pathlines(Pathlines& pl, LoadReport& report, const std::string& file) { Repair(pl, report, file).run(); }

}  // namespace pathlet::io
