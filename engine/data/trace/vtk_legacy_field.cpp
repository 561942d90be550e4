// VTK legacy STRUCTURED_POINTS reader for velocity volumes.
#include "field_readers.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <optional>

namespace pathlet::trace {
namespace {

// Byte cursor with line numbers, for messages "<file>: line N: ...".
struct Cursor {
    std::string_view b;
    std::string path;
    size_t pos = 0;
    size_t line = 1;

    [[noreturn]] void fail(const std::string& what) const {
        throw DataError(path + ": line " + std::to_string(line) + ": " + what);
    }
    bool at_end() {
        skip_space();
        return pos >= b.size();
    }
    void skip_space() {
        while (pos < b.size() && std::isspace(static_cast<unsigned char>(b[pos]))) line += b[pos++] == '\n';
    }
    std::string_view token() {
        skip_space();
        const size_t s = pos;
        while (pos < b.size() && !std::isspace(static_cast<unsigned char>(b[pos]))) ++pos;
        if (s == pos) fail("unexpected end of file");
        return b.substr(s, pos - s);
    }
    std::string_view rest_of_line() {
        const size_t s = pos;
        while (pos < b.size() && b[pos] != '\n') ++pos;
        std::string_view r = b.substr(s, pos - s);
        if (pos < b.size()) ++pos, ++line;
        return r;
    }
    double number() {
        std::string_view t = token();
        double v = 0.0;
        auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
        if (ec != std::errc() || p != t.data() + t.size()) fail("expected a number, got '" + std::string(t) + "'");
        return v;
    }
    long integer() {
        const double v = number();
        // Range first: casting nan, inf or 1e20 to an integer is undefined behaviour.
        if (!(v >= -9.0e15 && v <= 9.0e15) || v != std::trunc(v))
            fail("expected an integer, got " + std::string(std::isfinite(v) ? "a fraction or a huge number" : "nan/inf"));
        return long(v);
    }
};

size_t type_size(std::string_view t) {
    if (t == "unsigned_char" || t == "char" || t == "bit") return 1;
    if (t == "short" || t == "unsigned_short") return 2;
    if (t == "int" || t == "unsigned_int" || t == "float") return 4;
    if (t == "long" || t == "unsigned_long" || t == "double" || t == "vtktypeint64" || t == "vtktypeuint64") return 8;
    return 0;
}

// Big-endian binary value of type t to double.
double decode_be(const unsigned char* p, std::string_view t) {
    const size_t n = type_size(t);
    uint64_t u = 0;
    for (size_t i = 0; i < n; ++i) u = (u << 8) | p[i];
    if (t == "float") { uint32_t w = uint32_t(u); float f; std::memcpy(&f, &w, 4); return f; }
    if (t == "double") { double d; std::memcpy(&d, &u, 8); return d; }
    if (t == "char") return double(int8_t(u));
    if (t == "short") return double(int16_t(u));
    if (t == "int") return double(int32_t(u));
    if (t == "long" || t == "vtktypeint64") return double(int64_t(u));
    return double(u);
}

// `count` values of type t; ASCII or binary. Size is checked before allocating.
std::vector<float> read_values(Cursor& c, bool binary, std::string_view type, size_t count) {
    const size_t ts = type_size(type);
    if (ts == 0 || type == "bit") c.fail("unsupported data type '" + std::string(type) + "'");
    std::vector<float> out;
    if (binary) {
        if (count > (c.b.size() - c.pos) / ts)
            c.fail("declares " + std::to_string(count) + " values but only " + std::to_string(c.b.size() - c.pos) + " bytes remain");
        out.resize(count);
        const auto* p = reinterpret_cast<const unsigned char*>(c.b.data() + c.pos);
        for (size_t i = 0; i < count; ++i) out[i] = float(decode_be(p + i * ts, type));
        c.pos += count * ts;
    } else {
        if (count > (c.b.size() - c.pos) / 2 + 1) c.fail("declares " + std::to_string(count) + " values, more than the file can hold");
        out.resize(count);
        for (size_t i = 0; i < count; ++i) out[i] = float(c.number());
    }
    return out;
}

}  // namespace

VelocityField read_vtk_legacy_field(std::string_view bytes, const std::string& path) {
    Cursor c{bytes, path};
    if (c.rest_of_line().substr(0, 22) != "# vtk DataFile Version") c.line = 1, c.fail("not a VTK legacy file");
    c.rest_of_line();  // title
    const std::string_view enc = c.token();
    if (enc != "ASCII" && enc != "BINARY") c.fail("expected ASCII or BINARY, got '" + std::string(enc) + "'");
    const bool binary = enc == "BINARY";
    if (c.token() != "DATASET") c.fail("expected DATASET");
    if (const auto ds = c.token(); ds != "STRUCTURED_POINTS")
        c.fail("dataset " + std::string(ds) + " is not a velocity volume (need STRUCTURED_POINTS)");

    VelocityField f;
    f.source = path;
    std::optional<size_t> npoints;
    bool seen_dims = false;
    std::vector<float> vec;
    while (!c.at_end()) {
        const std::string_view kw = c.token();
        if (kw == "DIMENSIONS") {
            // Once, before the data: a second one would resize the grid under arrays already read.
            if (npoints || seen_dims) c.fail("DIMENSIONS given twice, or after POINT_DATA");
            seen_dims = true;
            for (int a = 0; a < 3; ++a) {
                const long d = c.integer();
                if (d < 1 || d > 100000) c.fail("bad dimension " + std::to_string(d));
                f.grid.dims[a] = int(d);
            }
        } else if (kw == "SPACING" || kw == "ASPECT_RATIO") {
            for (int a = 0; a < 3; ++a) f.grid.spacing[a] = float(c.number());
        } else if (kw == "ORIGIN") {
            for (int a = 0; a < 3; ++a) f.grid.origin[a] = float(c.number());
        } else if (kw == "POINT_DATA") {
            if (npoints) c.fail("POINT_DATA given twice (one grid per file)");
            const long n = c.integer();
            if (n < 0) c.fail("negative POINT_DATA count");
            npoints = size_t(n);
            if (*npoints != f.grid.count()) c.fail("POINT_DATA " + std::to_string(*npoints) + " does not match DIMENSIONS");
        } else if (kw == "SCALARS" || kw == "VECTORS") {
            if (!npoints) c.fail(std::string(kw) + " before POINT_DATA");
            const std::string name(c.token());
            const std::string type(c.token());
            size_t comps = kw == "VECTORS" ? 3 : 1;
            std::string_view tail = c.rest_of_line();  // optional component count for SCALARS
            if (kw == "SCALARS" && !tail.empty() && tail.find_first_not_of(" \t\r") != std::string_view::npos)
                comps = size_t(std::clamp(std::atoi(std::string(tail).c_str()), 1, 4));  // VTK: 1..4
            if (kw == "SCALARS") {
                if (c.token() != "LOOKUP_TABLE") c.fail("expected LOOKUP_TABLE after SCALARS");
                c.rest_of_line();
            }
            auto values = read_values(c, binary, type, *npoints * comps);
            if (kw == "VECTORS" && vec.empty()) {
                vec = std::move(values);
            } else if (kw == "SCALARS" && f.scalars.empty()) {
                f.scalars.resize(*npoints);
                for (size_t i = 0; i < *npoints; ++i) f.scalars[i] = values[i * comps];
                f.scalars_name = name;
            }
        } else if (kw == "METADATA") {
            while (c.pos < c.b.size() && !c.rest_of_line().empty()) {}
        } else if (kw == "CELL_DATA" || kw == "FIELD") {
            break;  // nothing after this is point data we can use without parsing it all
        } else {
            c.fail("unexpected keyword '" + std::string(kw) + "'");
        }
    }
    if (!npoints) c.fail("no POINT_DATA");
    if (vec.empty()) c.fail("no VECTORS in POINT_DATA (a velocity field needs them)");
    f.frames.assign(1, std::vector<glm::vec3>(*npoints));
    for (size_t i = 0; i < *npoints; ++i) f.frames[0][i] = {vec[3 * i], vec[3 * i + 1], vec[3 * i + 2]};
    f.frame_times = {0.0f};
    f.check();
    return f;
}

}  // namespace pathlet::trace
