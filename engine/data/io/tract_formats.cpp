// TrackVis .trk and MRtrix .tck readers and writers (io/tract_formats.hpp).
#include "tract_formats.hpp"

#include "byte_reader.hpp"
#include "raw_polylines.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>

namespace pathlet::io {

namespace {

template <class T>
T load(std::string_view b, size_t at, bool big) {
    T v;
    std::memcpy(&v, b.data() + at, sizeof v);
    if (big != (std::endian::native == std::endian::big)) {
        unsigned char x[sizeof v];
        std::memcpy(x, &v, sizeof v);
        std::reverse(x, x + sizeof v);
        std::memcpy(&v, x, sizeof v);
    }
    return v;
}

template <class T>
void store(std::string& s, T v, bool big) {
    unsigned char x[sizeof v];
    std::memcpy(x, &v, sizeof v);
    if (big != (std::endian::native == std::endian::big)) std::reverse(x, x + sizeof v);
    s.append(reinterpret_cast<const char*>(x), sizeof v);
}

std::string fmt_g(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
}

// Running min/max of a named value, for the report ("FA (per point, 0.1 .. 0.9)").
struct Range {
    double lo = INFINITY, hi = -INFINITY;
    void add(float v) {
        if (std::isfinite(v)) lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
    }
    std::string text() const { return lo <= hi ? fmt_g(lo) + " .. " + fmt_g(hi) : "no finite values"; }
};

// ---- TrackVis ------------------------------------------------------------------------------

constexpr size_t kTrkHeader = 1000;
constexpr int kTrkMaxValues = 1000;  // scalars or properties per point/track: far beyond any real file

// A header name slot (20 bytes): the name up to its NUL; TrackVis stores a count > 1 in the
// last byte when one name stands for several values ("rgb\0...\3").
struct TrkName {
    std::string name;
    int count = 1;
};
std::vector<TrkName> trk_names(std::string_view h, size_t at, int values, const char* generic) {
    std::vector<TrkName> out;
    int named = 0;
    for (int k = 0; k < 10 && named < values; ++k) {
        std::string_view slot = h.substr(at + 20 * size_t(k), 20);
        const size_t nul = std::min(slot.find('\0'), slot.size());
        std::string name(slot.substr(0, nul));
        for (char& c : name)
            if ((unsigned char)c < 0x20 || (unsigned char)c >= 0x7f) c = '?';
        if (name.empty()) break;
        int count = nul < 19 && (unsigned char)slot[19] > 1 ? (unsigned char)slot[19] : 1;
        count = std::min(count, values - named);
        out.push_back({name, count});
        named += count;
    }
    for (int k = named; k < values; ++k) out.push_back({std::string(generic) + std::to_string(k), 1});
    return out;
}

// TrackVis's axis codes (voxel_order, or the matrix's dominant axes) -> per voxel axis the
// world axis (0 x/R-L, 1 y/A-P, 2 z/S-I) and its sign (+1 towards R, A, S). False if the
// code is not a permutation of the three axes.
bool axis_codes(std::string_view code, int axis[3], int sign[3]) {
    if (code.size() < 3) return false;
    bool seen[3] = {false, false, false};
    for (int k = 0; k < 3; ++k) {
        const char c = char(std::toupper((unsigned char)code[size_t(k)]));
        const char* letters = "RLAPSI";
        const char* p = std::strchr(letters, c);
        if (!p || !c) return false;
        const int i = int(p - letters);
        axis[k] = i / 2;
        sign[k] = i % 2 == 0 ? 1 : -1;
        if (seen[axis[k]]) return false;
        seen[axis[k]] = true;
    }
    return true;
}

// The header's voxmm -> world transform: vox_to_ras (row-major, version 2, used when its [3][3]
// is not 0) applied to voxel indices, or the identity (points stay voxmm) with a warning.
struct TrkTransform {
    glm::mat4 voxmm_to_world{1.0f};
    bool has_matrix = false;
};
TrkTransform trk_transform(std::string_view b, const std::string& file, bool big, int version, LoadReport& report) {
    glm::ivec3 dims;
    glm::vec3 vs;
    for (int k = 0; k < 3; ++k) {
        dims[k] = load<int16_t>(b, 6 + 2 * size_t(k), big);
        vs[k] = load<float>(b, 12 + 4 * size_t(k), big);
    }
    // vox_to_ras, row-major; recorded when its [3][3] is not 0 (version 2 only).
    glm::mat4 A(1.0f);
    bool has_matrix = false;
    if (version == 2) {
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) A[c][r] = load<float>(b, 440 + 4 * size_t(4 * r + c), big);
        has_matrix = A[3][3] != 0.0f;
        for (int r = 0; r < 4 && has_matrix; ++r)
            for (int c = 0; c < 4; ++c)
                if (!std::isfinite(A[c][r])) fail_at(file, at_byte(440 + 4 * size_t(4 * r + c)), "vox_to_ras holds a non-finite value");
    }
    // Points are "voxmm": voxel index + 0.5 (TrackVis counts from the voxel corner) times the
    // voxel size. RAS mm = vox_to_ras * (voxel index), with the axes reordered where
    // voxel_order and the matrix disagree (as nibabel does).
    glm::mat4 voxmm_to_world(1.0f);
    if (has_matrix) {
        for (int k = 0; k < 3; ++k)
            if (!(vs[k] > 0.0f) || !std::isfinite(vs[k]))
                fail_at(file, at_byte(12 + 4 * size_t(k)), "voxel size " + fmt_g(vs[k]) + " must be positive to apply vox_to_ras");
        glm::mat4 to_index(1.0f);
        for (int k = 0; k < 3; ++k) to_index[k][k] = 1.0f / vs[k], to_index[3][k] = -0.5f;
        // The matrix's own axis codes: the dominant world axis of each voxel axis (column).
        char matrix_code[4] = {0, 0, 0, 0};
        for (int c = 0; c < 3; ++c) {
            int best = 0;
            for (int r = 1; r < 3; ++r)
                if (std::fabs(A[c][r]) > std::fabs(A[c][best])) best = r;
            matrix_code[c] = "RLAPSI"[2 * best + (A[c][best] < 0.0f ? 1 : 0)];
        }
        int ha[3], hs[3], ma[3], ms[3];
        std::string_view order = b.substr(948, 4);
        order = order.substr(0, std::min(order.find('\0'), order.size()));
        if (order.empty()) order = "LPS";  // TrackVis's default
        glm::mat4 reorder(0.0f);
        reorder[3][3] = 1.0f;
        if (axis_codes(order, ha, hs) && axis_codes(matrix_code, ma, ms)) {
            // Voxel axis k of the file runs along world axis ha[k]; it is the matrix's voxel
            // axis j with ma[j] == ha[k], reversed when their directions differ.
            for (int k = 0; k < 3; ++k)
                for (int j = 0; j < 3; ++j) {
                    if (ma[j] != ha[k]) continue;
                    const bool flip = hs[k] != ms[j];
                    if (flip && dims[k] <= 0)
                        fail_at(file, at_byte(6 + 2 * size_t(k)), "dimension " + std::to_string(dims[k]) +
                                                                      " must be positive to flip voxel axis " + std::to_string(k));
                    reorder[k][j] = flip ? -1.0f : 1.0f;
                    if (flip) reorder[3][j] = float(dims[k] - 1);
                }
        } else {
            reorder = glm::mat4(1.0f);
            report.warnings.push_back("voxel_order '" + std::string(order) + "' is not a permutation of R/L, A/P, S/I: axes taken as the matrix's");
        }
        voxmm_to_world = A * reorder * to_index;
    } else {
        report.warnings.push_back(std::string(version == 1 ? "TrackVis v1 has" : "the header has") +
                                  " no voxel-to-RAS matrix: points stay in TrackVis voxmm coordinates");
    }

    return {voxmm_to_world, has_matrix};
}

// One report line a named per-point or per-track array, its value range over the file.
void report_trk_arrays(const std::vector<TrkName>& names, const std::vector<Range>& ranges, const char* per,
                       LoadReport& report) {
    size_t k = 0;
    for (const auto& s : names) {
        Range r;
        for (int c = 0; c < s.count; ++c, ++k) r.lo = std::min(r.lo, ranges[k].lo), r.hi = std::max(r.hi, ranges[k].hi);
        report.arrays.push_back(s.name + " (per " + per + (s.count > 1 ? ", " + std::to_string(s.count) + " comp" : "") + ", " +
                                r.text() + "; not drawn)");
    }
}

Pathlines read_trk_impl(std::string_view b, const std::string& file, LoadReport& report) {
    if (b.size() < kTrkHeader)
        fail_at(file, at_byte(b.size()), "a TrackVis header is 1000 bytes but the file has only " + std::to_string(b.size()) +
                                             " (truncated, or not a .trk file)");
    if (b.substr(0, 5) != "TRACK") fail_at(file, at_byte(0), "not a TrackVis file (the magic \"TRACK\" is missing)");
    // hdr_size (1000) tells the byte order.
    bool big = false;
    if (load<int32_t>(b, 996, false) != 1000) {
        if (load<int32_t>(b, 996, true) != 1000)
            fail_at(file, at_byte(996), "hdr_size is " + std::to_string(load<int32_t>(b, 996, false)) +
                                            ", not 1000 (corrupt header, or not a TrackVis file)");
        big = true;
    }
    const int version = load<int32_t>(b, 992, big);
    if (version != 1 && version != 2)
        fail_at(file, at_byte(992), "TrackVis version " + std::to_string(version) + " is not supported (1 or 2)");
    const int ns = load<int16_t>(b, 36, big), np = load<int16_t>(b, 238, big);
    if (ns < 0 || ns > kTrkMaxValues) fail_at(file, at_byte(36), "n_scalars " + std::to_string(ns) + " is out of range (0.." + std::to_string(kTrkMaxValues) + ")");
    if (np < 0 || np > kTrkMaxValues)
        fail_at(file, at_byte(238), "n_properties " + std::to_string(np) + " is out of range (0.." + std::to_string(kTrkMaxValues) + ")");
    const auto [voxmm_to_world, has_matrix] = trk_transform(b, file, big, version, report);

    const auto scalars = trk_names(b, 38, ns, "scalar_");
    const auto props = trk_names(b, 240, np, "property_");
    std::vector<Range> srange(static_cast<size_t>(ns)), prange(static_cast<size_t>(np));
    const int32_t declared = load<int32_t>(b, 988, big);
    if (declared < 0) fail_at(file, at_byte(988), "n_count " + std::to_string(declared) + " is negative");

    Pathlines pl;
    pl.units.length = "mm";
    size_t at = kTrkHeader, empty_tracks = 0;
    const size_t per_point = 3 + size_t(ns);
    uint64_t tracks = 0;
    while (at < b.size() && (declared == 0 || tracks < uint64_t(declared))) {
        if (b.size() - at < 4) fail_at(file, at_byte(at), "a track's point count is cut off (file truncated?)");
        const int32_t m = load<int32_t>(b, at, big);
        if (m < 0) fail_at(file, at_byte(at), "track " + std::to_string(tracks) + " has a negative point count " + std::to_string(m));
        const uint64_t need = (uint64_t(m) * per_point + uint64_t(np)) * 4;
        if (need > b.size() - at - 4)
            fail_at(file, at_byte(at), "track " + std::to_string(tracks) + " declares " + std::to_string(m) + " points (" +
                                           std::to_string(need) + " bytes) but only " + std::to_string(b.size() - at - 4) +
                                           " remain (file truncated, or a corrupt count)");
        at += 4;
        if (m == 0) ++empty_tracks;
        const uint32_t first = uint32_t(pl.position.size());
        if (pl.position.size() + size_t(m) > std::numeric_limits<uint32_t>::max())
            fail_at(file, at_byte(at), "more than 2^32 points");
        for (int32_t i = 0; i < m; ++i, at += per_point * 4) {
            glm::vec4 p(load<float>(b, at, big), load<float>(b, at + 4, big), load<float>(b, at + 8, big), 1.0f);
            pl.position.push_back(glm::vec3(voxmm_to_world * p));
            for (int k = 0; k < ns; ++k) srange[size_t(k)].add(load<float>(b, at + 12 + 4 * size_t(k), big));
        }
        for (int k = 0; k < np; ++k, at += 4) prange[size_t(k)].add(load<float>(b, at, big));
        if (m > 0) pl.lines.push_back({first, uint32_t(m)});
        ++tracks;
    }
    if (declared > 0 && tracks < uint64_t(declared))
        fail_at(file, at_byte(at), "n_count declares " + std::to_string(declared) + " tracks but the file ends after " +
                                       std::to_string(tracks) + " (truncated?)");
    if (at < b.size())
        report.warnings.push_back("ignored " + std::to_string(b.size() - at) + " bytes after the " + std::to_string(tracks) +
                                  " tracks n_count declares");
    if (empty_tracks) report.warnings.push_back("skipped " + std::to_string(empty_tracks) + " tracks without points");

    report.format = "TrackVis .trk v" + std::to_string(version) + (big ? ", big-endian" : ", little-endian") +
                    (has_matrix ? ", voxel-to-RAS" : ", voxmm");
    report_trk_arrays(scalars, srange, "point", report);
    report_trk_arrays(props, prange, "track", report);
    return pl;
}

// ---- MRtrix ---------------------------------------------------------------------------------

constexpr size_t kTckMaxHeader = 1 << 20;

Pathlines read_tck_impl(std::string_view b, const std::string& file, LoadReport& report) {
    Cursor c(b.substr(0, std::min(b.size(), kTckMaxHeader)), file);
    if (c.rest_of_line() != "mrtrix tracks") c.fail_byte(0, "not an MRtrix .tck file (the first line must be 'mrtrix tracks')");
    std::map<std::string, std::string> keys;
    bool ended = false;
    while (!c.at_end()) {
        const std::string_view line = c.rest_of_line();
        if (line == "END") {
            ended = true;
            break;
        }
        const size_t colon = line.find(':');
        if (colon == std::string_view::npos) {
            if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
            c.fail("header line '" + std::string(line.substr(0, 40)) + "' is not 'key: value'");
        }
        std::string key(line.substr(0, colon)), value(line.substr(colon + 1));
        value.erase(0, value.find_first_not_of(' '));
        keys[key] = value;  // a repeated key (e.g. command_history) keeps its last value
    }
    if (!ended)
        c.fail(b.size() > kTckMaxHeader ? "no END line in the first 1 MiB of the header"
                                         : "the header has no END line (file truncated?)");
    const size_t header_end = c.pos();
    auto need = [&](const char* key) -> const std::string& {
        auto it = keys.find(key);
        if (it == keys.end()) c.fail_byte(0, std::string("the header has no '") + key + ":' line");
        return it->second;
    };
    const std::string& dt = need("datatype");
    size_t width = 0;
    bool big = false;
    if (dt == "Float32LE" || dt == "Float32BE") width = 4;
    else if (dt == "Float64LE" || dt == "Float64BE") width = 8;
    else c.fail_byte(0, "datatype '" + dt.substr(0, 40) + "' is not supported (Float32LE/BE, Float64LE/BE)");
    big = dt.back() == 'E' && dt[dt.size() - 2] == 'B';
    const std::string& where = need("file");
    uint64_t offset = 0;
    {
        Cursor f(where, file);
        if (f.token() != ".") c.fail_byte(0, "'file: " + where.substr(0, 40) + "': the data must be in this file ('file: . OFFSET')");
        auto t = f.token();
        int64_t v = 0;
        if (!parse_number(t, v) || v < int64_t(header_end) || uint64_t(v) > b.size())
            c.fail_byte(0, "'file: " + where.substr(0, 40) + "': the data offset must lie between the header's end (" +
                               std::to_string(header_end) + ") and the file's end (" + std::to_string(b.size()) + ")");
        offset = uint64_t(v);
    }
    Pathlines pl;
    pl.units.length = "mm";
    const size_t triplet = 3 * width;
    size_t at = size_t(offset), empty_tracks = 0;
    bool done = false;
    uint32_t first = 0;
    auto value = [&](size_t p) { return width == 4 ? double(load<float>(b, p, big)) : load<double>(b, p, big); };
    while (b.size() - at >= triplet) {
        const double x = value(at), y = value(at + width), z = value(at + 2 * width);
        at += triplet;
        if (std::isinf(x) && std::isinf(y) && std::isinf(z)) {
            done = true;
            break;
        }
        if (std::isnan(x) && std::isnan(y) && std::isnan(z)) {  // end of a track
            const uint32_t n = uint32_t(pl.position.size()) - first;
            if (n > 0) pl.lines.push_back({first, n});
            else ++empty_tracks;
            first = uint32_t(pl.position.size());
            continue;
        }
        if (pl.position.size() >= std::numeric_limits<uint32_t>::max()) fail_at(file, at_byte(at), "more than 2^32 points");
        pl.position.push_back(glm::vec3(float(x), float(y), float(z)));
    }
    if (!done)
        fail_at(file, at_byte(b.size()), "the data end without the end-of-file marker (an Inf triplet): file truncated?");
    if (pl.position.size() > first) {
        pl.lines.push_back({first, uint32_t(pl.position.size() - first)});
        report.warnings.push_back("the last track has no end (NaN triplet): kept as it is");
    }
    if (empty_tracks) report.warnings.push_back("skipped " + std::to_string(empty_tracks) + " tracks without points");
    if (auto it = keys.find("count"); it != keys.end()) {
        int64_t n = -1;
        if (parse_number(std::string_view(it->second), n) && n >= 0 && uint64_t(n) != pl.lines.size() + empty_tracks)
            report.warnings.push_back("the header says count: " + it->second + " but the file holds " +
                                      std::to_string(pl.lines.size() + empty_tracks) + " tracks");
    }
    report.format = "MRtrix .tck, " + dt;
    return pl;
}

}  // namespace

Pathlines read_trk(std::string_view bytes, const std::string& file, LoadReport& report) {
    Pathlines pl = read_trk_impl(bytes, file, report);
    if (pl.lines.empty()) report.warnings.push_back("the file holds no tracks: empty pathline set");
    repair_pathlines(pl, report, file);
    return pl;
}

Pathlines read_tck(std::string_view bytes, const std::string& file, LoadReport& report) {
    Pathlines pl = read_tck_impl(bytes, file, report);
    if (pl.lines.empty()) report.warnings.push_back("the file holds no tracks: empty pathline set");
    repair_pathlines(pl, report, file);
    return pl;
}

std::string write_trk(const Pathlines& pl, const TrkWriteOptions& o) {
    const bool big = o.big_endian;
    std::string h(kTrkHeader, '\0');
    std::memcpy(h.data(), "TRACK", 5);
    auto put = [&](size_t at, auto v) {
        std::string tmp;
        store(tmp, v, big);
        std::memcpy(h.data() + at, tmp.data(), tmp.size());
    };
    for (int k = 0; k < 3; ++k) put(6 + 2 * size_t(k), int16_t(o.dims[k])), put(12 + 4 * size_t(k), o.voxel_size[k]);
    put(36, int16_t(o.scalars));
    for (int k = 0; k < std::min(o.scalars, 10); ++k) std::snprintf(h.data() + 38 + 20 * k, 20, "s%d", k);
    put(238, int16_t(o.properties));
    for (int k = 0; k < std::min(o.properties, 10); ++k) std::snprintf(h.data() + 240 + 20 * k, 20, "p%d", k);
    if (o.version == 2)
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) put(440 + 4 * size_t(4 * r + c), o.vox_to_ras[c][r]);
    std::memcpy(h.data() + 948, o.voxel_order.data(), std::min<size_t>(o.voxel_order.size(), 3));
    put(988, int32_t(o.write_count ? pl.lines.size() : 0));
    put(992, int32_t(o.version));
    put(996, int32_t(kTrkHeader));
    // World (RAS mm) back to voxmm; the voxel order is taken to agree with the matrix.
    glm::mat4 to_voxmm(1.0f);
    if (o.version == 2 && o.vox_to_ras[3][3] != 0.0f) {  // [3][3] = 0: "not recorded", points stay voxmm
        glm::mat4 from_index(1.0f);
        for (int k = 0; k < 3; ++k) from_index[k][k] = o.voxel_size[k], from_index[3][k] = 0.5f * o.voxel_size[k];
        to_voxmm = from_index * glm::inverse(o.vox_to_ras);
    }
    std::string s = h;
    for (size_t j = 0; j < pl.lines.size(); ++j) {
        const LineRange r = pl.lines[j];
        store(s, int32_t(r.count), big);
        for (uint32_t i = 0; i < r.count; ++i) {
            const glm::vec3 p(to_voxmm * glm::vec4(pl.position[r.first + i], 1.0f));
            for (int k = 0; k < 3; ++k) store(s, p[k], big);
            for (int k = 0; k < o.scalars; ++k) store(s, float(i) + 0.1f * float(k), big);
        }
        for (int k = 0; k < o.properties; ++k) store(s, float(j) + 0.1f * float(k), big);
    }
    return s;
}

std::string write_tck(const Pathlines& pl, const TckWriteOptions& o) {
    const std::string dt = std::string(o.float64 ? "Float64" : "Float32") + (o.big_endian ? "BE" : "LE");
    // The offset is part of the header it points past: pad it to a fixed width.
    std::string head = "mrtrix tracks\ndatatype: " + dt + "\ncount: " + std::to_string(pl.lines.size()) + "\nfile: . ";
    const size_t offset = head.size() + 10 + 5;  // 10 digits, "\nEND\n"
    char num[16];
    std::snprintf(num, sizeof num, "%010zu", offset);
    std::string s = head + num + "\nEND\n";
    auto triplet = [&](double x, double y, double z) {
        for (double v : {x, y, z}) o.float64 ? store(s, v, o.big_endian) : store(s, float(v), o.big_endian);
    };
    for (auto& r : pl.lines) {
        for (uint32_t i = 0; i < r.count; ++i) {
            const glm::vec3 p = pl.position[r.first + i];
            triplet(p.x, p.y, p.z);
        }
        triplet(NAN, NAN, NAN);
    }
    if (o.end_marker) triplet(INFINITY, INFINITY, INFINITY);
    return s;
}

}  // namespace pathlet::io
