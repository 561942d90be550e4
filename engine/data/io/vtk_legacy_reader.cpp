// VTK legacy POLYDATA reader: ASCII and BINARY (big-endian), 4.2 "LINES n size" and 5.1
// OFFSETS/CONNECTIVITY layouts, point arrays from SCALARS, VECTORS and FIELD. Other
// sections are read by their declared size and discarded.
#include "pathline_formats.hpp"
#include "units.hpp"
#include "vtk_values.hpp"

#include <cmath>

namespace pathlet::io {

void check_fits(Cursor& c, uint64_t count, ScalarType type, bool binary, const char* what) {
    uint64_t rem = c.remaining();
    bool ok = binary ? count <= rem / scalar_size(type) : count <= (rem + 1) / 2;
    if (!ok)
        c.fail(std::string(what) + ": declares " + std::to_string(count) + " values, more than the " + std::to_string(rem) +
               " bytes left in the file can hold (truncated file or corrupt count)");
}

namespace {

std::vector<std::string_view> split(std::string_view line) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        size_t b = i;
        while (i < line.size() && !is_space(line[i])) ++i;
        if (i > b) out.push_back(line.substr(b, i - b));
    }
    return out;
}

constexpr const char* kByteOrderHint =
    "; the values look little-endian, but VTK legacy BINARY data must be big-endian (was the file written by a "
    "non-VTK tool? re-export it with VTK or as ASCII)";

bool swapped_fits(int64_t v, ScalarType t, int64_t lo, int64_t hi) {
    uint64_t u = uint64_t(v);
    int64_t s = scalar_size(t) == 8 ? int64_t(__builtin_bswap64(u)) : scalar_size(t) == 4 ? int64_t(int32_t(__builtin_bswap32(uint32_t(u)))) : v;
    return s >= lo && s <= hi;
}

struct LegacyReader {
    Cursor c;
    LoadReport& report;
    bool binary = false;
    int version_major = 0;
    RawPolylines raw;
    uint64_t n_points = 0;
    bool have_points = false;

    LegacyReader(std::string_view bytes, const std::string& file, LoadReport& r) : c(bytes, file), report(r) {}

    // The next non-blank line, split into tokens ("" at end of file).
    std::vector<std::string_view> next_line() {
        c.skip_space();
        return split(c.rest_of_line());
    }
    ScalarType type_of(std::string_view name) {
        auto t = legacy_type(name);
        if (!t) c.fail("unknown data type '" + std::string(name) + "'");
        if (binary && iequals(name, "bit")) c.fail("packed 'bit' arrays are not supported in BINARY files");
        return *t;
    }
    uint64_t num(std::string_view tok, const char* what, uint64_t max = UINT32_MAX) {
        int64_t v;
        if (!parse_number(tok, v)) c.fail(std::string("expected ") + what + ", got '" + std::string(tok) + "'");
        if (v < 0 || uint64_t(v) > max) c.fail(std::string(what) + " " + std::string(tok) + " is out of range");
        return uint64_t(v);
    }
    void need(const std::vector<std::string_view>& t, size_t n, const char* form) {
        if (t.size() < n) c.fail(std::string("malformed line, expected '") + form + "'");
    }
    std::vector<float> floats(uint64_t count, ScalarType t, const char* what) {
        return read_values<float>(c, count, t, binary, true, what);
    }
    std::vector<int64_t> ints(uint64_t count, ScalarType t, const char* what) {
        return read_values<int64_t>(c, count, t, binary, true, what);
    }
    // `count` strings of a string array as vtkDataWriter writes them: ASCII one per line with
    // %XX escapes; BINARY each after a big-endian length whose top two bits give its size
    // (11: 6-bit length in 1 byte, 10: 14 bits in 2, 01: 30 bits in 4, 00: 64 bits in 8).
    std::vector<std::string> strings(uint64_t count, const std::string& what) {
        if (count > c.remaining() + 1) c.fail(what + ": declares " + std::to_string(count) + " strings, more than the file holds");
        std::vector<std::string> out;
        for (uint64_t i = 0; i < count; ++i) {
            if (c.at_end()) c.fail(what + ": the file ends after " + std::to_string(i) + " of " + std::to_string(count) + " strings");
            std::string s;
            if (!binary) {
                std::string_view line = c.rest_of_line();
                auto hex = [](char h) { return h >= '0' && h <= '9' ? h - '0' : h >= 'a' && h <= 'f' ? h - 'a' + 10 : h >= 'A' && h <= 'F' ? h - 'A' + 10 : -1; };
                for (size_t k = 0; k < line.size(); ++k) {
                    if (line[k] == '%' && k + 2 < line.size() && hex(line[k + 1]) >= 0 && hex(line[k + 2]) >= 0) {
                        s += char(hex(line[k + 1]) * 16 + hex(line[k + 2]));
                        k += 2;
                    } else {
                        s += line[k];
                    }
                }
            } else {
                const auto b0 = (unsigned char)c.bytes(1, what.c_str())[0];
                const int extra = b0 >> 6 == 3 ? 0 : b0 >> 6 == 2 ? 1 : b0 >> 6 == 1 ? 3 : 7;
                uint64_t len = b0 & 0x3f;
                for (unsigned char b : c.bytes(size_t(extra), what.c_str())) len = (len << 8) | b;
                if (len > c.remaining())
                    c.fail(what + ": string " + std::to_string(i) + " declares " + std::to_string(len) + " bytes but only " +
                           std::to_string(c.remaining()) + " remain (file truncated?)");
                s = std::string(c.bytes(size_t(len), what.c_str()));
            }
            out.push_back(std::move(s));
        }
        return out;
    }

    // METADATA blocks (VTK >= 8) end at the first blank line.
    void skip_metadata() {
        c.rest_of_line();
        while (!c.at_end()) {
            auto l = c.rest_of_line();
            if (split(l).empty()) break;
        }
    }

    void read_header() {
        auto l1 = c.rest_of_line();
        if (l1.size() < 14 || !iequals(l1.substr(0, 14), "# vtk DataFile"))
            c.fail("not a VTK legacy file (first line must be '# vtk DataFile Version x.y')");
        auto vpos = l1.find_last_of(' ');
        std::string_view ver = l1.substr(vpos + 1);
        version_major = std::isdigit((unsigned char)ver.empty() ? 'x' : ver[0]) ? ver[0] - '0' : 0;
        c.rest_of_line();  // free-form title: never parsed
        auto enc = split(c.rest_of_line());
        if (enc.empty()) c.fail("expected ASCII or BINARY on line 3");
        if (iequals(enc[0], "BINARY")) binary = true;
        else if (!iequals(enc[0], "ASCII")) c.fail("expected ASCII or BINARY on line 3, got '" + std::string(enc[0]) + "'");
        report.format = "VTK legacy " + std::string(ver) + (binary ? " BINARY" : " ASCII");
        if (binary) c.set_text_locations(false);
        auto ds = next_line();
        if (ds.size() < 2 || !iequals(ds[0], "DATASET")) c.fail("expected 'DATASET POLYDATA'");
        if (!iequals(ds[1], "POLYDATA"))
            c.fail("DATASET " + std::string(ds[1]) + " is not supported: pathlines must be POLYDATA with LINES");
    }

    // Cells of one topology section, as offsets + connectivity. Layout by the OFFSETS keyword.
    void read_cells(const std::vector<std::string_view>& t, bool keep, const char* kind) {
        need(t, 3, "LINES n size");
        std::string where = c.where();
        uint64_t a = num(t[1], "cell count"), b = num(t[2], "cell array size", UINT64_MAX / 16);
        size_t save = c.pos();
        c.skip_space();
        bool layout51 = c.remaining() >= 7 && iequals(c.data().substr(c.pos(), 7), "OFFSETS");
        c.seek(save);
        std::vector<int64_t> offsets, conn;
        if (layout51) {
            auto ot = next_line();
            need(ot, 2, "OFFSETS type");
            ScalarType oty = type_of(ot[1]);
            offsets = ints(a, oty, "OFFSETS");
            auto ct = next_line();
            if (ct.size() < 2 || !iequals(ct[0], "CONNECTIVITY")) c.fail("expected 'CONNECTIVITY type' after OFFSETS");
            ScalarType cty = type_of(ct[1]);
            conn = ints(b, cty, "CONNECTIVITY");
            if (offsets.empty()) offsets.push_back(0);
            if (binary && keep && uint64_t(offsets.back()) != b && swapped_fits(offsets.back(), oty, 0, int64_t(b)))
                c.fail(std::string(kind) + " offsets end at " + std::to_string(offsets.back()) + ", not " + std::to_string(b) + kByteOrderHint);
            if (binary && keep)
                for (auto v : conn)
                    if ((v < 0 || uint64_t(v) >= n_points) && swapped_fits(v, cty, 0, int64_t(n_points) - 1))
                        c.fail(std::string(kind) + " connectivity index " + std::to_string(v) + " is out of range" + kByteOrderHint);
        } else {
            // 4.2: b integers, each cell "k i0 .. ik-1".
            auto cells = ints(b, ScalarType::I32, kind);  // b checked against the file's size
            // Every cell takes at least its count value: a cell count beyond the values is a lie,
            // caught before it sizes an allocation.
            if (a > cells.size())
                c.fail(std::string(kind) + " declares " + std::to_string(a) + " cells but only " +
                       std::to_string(cells.size()) + " values (counts disagree)");
            offsets.reserve(a + 1);
            offsets.push_back(0);
            conn.reserve(b > a ? b - a : 0);
            size_t i = 0;
            for (uint64_t cell = 0; cell < a; ++cell) {
                if (i >= cells.size())
                    c.fail(std::string(kind) + " declares " + std::to_string(a) + " cells in " + std::to_string(b) +
                           " values, but the values end after " + std::to_string(cell) + " cells (counts disagree)");
                int64_t k = cells[i++];
                if (k < 0 || uint64_t(k) > cells.size() - i) {
                    std::string msg = std::string(kind) + " cell " + std::to_string(cell) + " claims " + std::to_string(k) +
                                      " points but only " + std::to_string(cells.size() - i) + " values remain (counts disagree)";
                    if (binary && swapped_fits(k, ScalarType::I32, 0, int64_t(cells.size() - i))) msg += kByteOrderHint;
                    c.fail(msg);
                }
                conn.insert(conn.end(), cells.begin() + i, cells.begin() + i + k);
                i += size_t(k);
                offsets.push_back(int64_t(conn.size()));
            }
            if (i != cells.size())
                c.fail(std::string(kind) + " declares size " + std::to_string(b) + " but its " + std::to_string(a) +
                       " cells use " + std::to_string(i) + " values (counts disagree)");
        }
        if (keep) {
            if (raw.line_count() > 0) c.fail("a second LINES section is not supported");
            raw.offsets = std::move(offsets);
            raw.connectivity = std::move(conn);
            raw.where_lines = where;
        } else {
            raw.polygons += offsets.empty() ? 0 : offsets.size() - 1;
        }
    }

    void add_point_array(std::string name, int comps, std::vector<float>&& v) {
        raw.point_arrays.push_back({std::move(name), comps, std::move(v)});
    }

    void read_field(const std::vector<std::string_view>& t, bool point_data, uint64_t tuples) {
        need(t, 3, "FIELD name nArrays");
        uint64_t n = num(t[2], "FIELD array count", 1u << 20);
        for (uint64_t i = 0; i < n; ++i) {
            auto a = next_line();
            while (!a.empty() && iequals(a[0], "METADATA")) { skip_metadata(); a = next_line(); }
            if (a.empty()) c.fail("FIELD declares " + std::to_string(n) + " arrays but the file ends after " + std::to_string(i));
            if (iequals(a[0], "NULL_ARRAY")) continue;
            need(a, 4, "arrayName numComponents numTuples type");
            uint64_t comps = num(a[1], "component count", 1u << 16), nt = num(a[2], "tuple count", UINT64_MAX / 1024);
            if (iequals(a[3], "string") || iequals(a[3], "utf8_string")) {
                auto strs = strings(comps * nt, "FIELD array '" + std::string(a[0]) + "'");
                const int which = unit_array_index(a[0]);
                if (!point_data && which >= 0 && !strs.empty()) {
                    const std::string unit = sanitize_unit(strs[0]);
                    if (unit.empty()) report.warnings.push_back("field data '" + std::string(a[0]) + "' holds no printable unit: ignored");
                    else unit_slot(raw.units, which) = unit;
                }
                continue;  // string arrays other than the units are not used
            }
            auto vals = floats(comps * nt, type_of(a[3]), "FIELD array");
            if (point_data) {
                if (nt != tuples)
                    c.fail("FIELD array '" + std::string(a[0]) + "' has " + std::to_string(nt) + " tuples but POINT_DATA declares " +
                           std::to_string(tuples) + " (counts disagree)");
                add_point_array(std::string(a[0]), int(comps), std::move(vals));
            }
        }
    }

    RawPolylines run() {
        read_header();
        enum { None, Point, Cell } section = None;
        uint64_t tuples = 0;
        while (true) {
            auto t = next_line();
            if (t.empty()) {
                if (c.at_end()) break;
                continue;
            }
            auto kw = t[0];
            if (iequals(kw, "POINTS")) {
                need(t, 3, "POINTS n type");
                n_points = num(t[1], "point count");
                auto ty = type_of(t[2]);
                raw.points = floats(n_points * 3, ty, "POINTS");
                if (binary && floats_look_garbled(raw.points.data(), raw.points.size())) {
                    std::vector<float> swapped(raw.points.size());
                    decode_floats(c.data().data() + c.pos() - raw.points.size() * scalar_size(ty), raw.points.size(), ty, false, swapped.data());
                    if (!floats_look_garbled(swapped.data(), swapped.size()))
                        c.fail_byte(c.pos() - raw.points.size() * scalar_size(ty), "POINTS hold absurd values" + std::string(kByteOrderHint));
                }
                have_points = true;
            } else if (iequals(kw, "LINES")) {
                read_cells(t, true, "LINES");
            } else if (iequals(kw, "VERTICES") || iequals(kw, "POLYGONS") || iequals(kw, "TRIANGLE_STRIPS")) {
                uint64_t before = raw.polygons;
                read_cells(t, false, "cells");
                if (iequals(kw, "VERTICES")) raw.polygons = before;  // only surfaces feed the "load it as a mesh" hint
            } else if (iequals(kw, "POINT_DATA") || iequals(kw, "CELL_DATA")) {
                need(t, 2, "POINT_DATA n");
                section = iequals(kw, "POINT_DATA") ? Point : Cell;
                tuples = num(t[1], "tuple count");
                if (section == Point) {
                    raw.where_data = c.where();
                    if (tuples != n_points)
                        c.fail("POINT_DATA declares " + std::to_string(tuples) + " tuples but POINTS declares " +
                               std::to_string(n_points) + " (counts disagree)");
                }
            } else if (iequals(kw, "FIELD")) {
                read_field(t, section == Point, tuples);
            } else if (iequals(kw, "METADATA")) {
                skip_metadata();
            } else if (section == None) {
                c.fail("unexpected keyword '" + std::string(kw.substr(0, 40)) + "' (expected POINTS, LINES, POINT_DATA...)");
            } else if (iequals(kw, "SCALARS")) {
                need(t, 3, "SCALARS name type [numComp]");
                uint64_t comps = t.size() >= 4 ? num(t[3], "component count", 4) : 1;
                auto ty = type_of(t[2]);
                // LOOKUP_TABLE is required by the spec, but tolerate writers that omit it.
                size_t save = c.pos();
                c.skip_space();
                if (c.remaining() >= 12 && iequals(c.data().substr(c.pos(), 12), "LOOKUP_TABLE")) c.rest_of_line();
                else c.seek(save);
                auto vals = floats(tuples * comps, ty, "SCALARS");
                if (section == Point) add_point_array(std::string(t[1]), int(comps), std::move(vals));
            } else if (iequals(kw, "VECTORS") || iequals(kw, "NORMALS")) {
                need(t, 3, "VECTORS name type");
                auto vals = floats(tuples * 3, type_of(t[2]), "VECTORS");
                if (section == Point && iequals(kw, "VECTORS")) add_point_array(std::string(t[1]), 3, std::move(vals));
            } else if (iequals(kw, "TEXTURE_COORDINATES")) {
                need(t, 4, "TEXTURE_COORDINATES name dim type");
                floats(tuples * num(t[2], "dimension", 3), type_of(t[3]), "TEXTURE_COORDINATES");
            } else if (iequals(kw, "TENSORS")) {
                need(t, 3, "TENSORS name type");
                floats(tuples * 9, type_of(t[2]), "TENSORS");
            } else if (iequals(kw, "COLOR_SCALARS")) {
                need(t, 3, "COLOR_SCALARS name nValues");
                floats(tuples * num(t[2], "value count", 4), binary ? ScalarType::U8 : ScalarType::F32, "COLOR_SCALARS");
            } else if (iequals(kw, "LOOKUP_TABLE")) {
                need(t, 3, "LOOKUP_TABLE name size");
                floats(4 * num(t[2], "table size"), binary ? ScalarType::U8 : ScalarType::F32, "LOOKUP_TABLE");
            } else {
                c.fail("unknown section '" + std::string(kw.substr(0, 40)) + "'; cannot skip it safely");
            }
        }
        if (!have_points && raw.line_count() > 0) c.fail("LINES without POINTS");
        return std::move(raw);
    }
};

}  // namespace

RawPolylines read_vtk_legacy(std::string_view bytes, const std::string& file, LoadReport& report) {
    return LegacyReader(bytes, file, report).run();
}

}  // namespace pathlet::io
