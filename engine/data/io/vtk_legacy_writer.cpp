// VTK legacy POLYDATA writer: time as SCALARS, velocity as VECTORS; BINARY is big-endian.
#include "pathline_formats.hpp"
#include "units.hpp"

#include <bit>
#include <cstdio>
#include <cstring>

namespace pathlet::io {

namespace {

struct Out {
    std::string s;
    bool binary;
    void text(const char* plain) { s += plain; }  // no arguments, so nothing to format
    void text(const char* fmt, auto first, auto... rest) {  // the header's fixed lines: well under 256
        char buf[256];
        const int n = std::snprintf(buf, sizeof buf, fmt, first, rest...);
        s.append(buf, size_t(n));
    }
    template <class T>
    void be(T v) {
        unsigned char b[sizeof(T)];
        std::memcpy(b, &v, sizeof v);
        if constexpr (std::endian::native == std::endian::little)
            for (size_t i = 0; i < sizeof(T); ++i) s += char(b[sizeof(T) - 1 - i]);
        else
            s.append(reinterpret_cast<char*>(b), sizeof b);
    }
    void floats(const float* v, size_t n, size_t per_line) {
        if (binary) {
            s.reserve(s.size() + n * 4 + 1);
            for (size_t i = 0; i < n; ++i) be(v[i]);
            s += '\n';
            return;
        }
        for (size_t i = 0; i < n; ++i) text((i + 1) % per_line == 0 || i + 1 == n ? "%.9g\n" : "%.9g ", double(v[i]));
    }
    void ints(const std::vector<int64_t>& v, bool i64, size_t per_line) {
        if (binary) {
            for (auto x : v) i64 ? be<int64_t>(x) : be<int32_t>(int32_t(x));
            s += '\n';
            return;
        }
        for (size_t i = 0; i < v.size(); ++i)
            text((i + 1) % per_line == 0 || i + 1 == v.size() ? "%lld\n" : "%lld ", (long long)v[i]);
    }
};

}  // namespace

std::string write_vtk_legacy(const Pathlines& pl, const VtkLegacyWriteOptions& opts) {
    Out o{{}, opts.binary};
    const size_t n = pl.position.size(), l = pl.lines.size();
    o.text("# vtk DataFile Version %s\npathlet pathlines\n%s\nDATASET POLYDATA\n", opts.version51 ? "5.1" : "4.2",
           opts.binary ? "BINARY" : "ASCII");
    // Known units as field data string arrays, as vtkDataWriter writes them (ASCII: one line
    // with %XX escapes; BINARY: a one-byte length 0b11xxxxxx, units being shorter than 64).
    const std::string* units[3] = {&pl.units.length, &pl.units.time, &pl.units.velocity};
    int known = 0;
    for (auto* u : units) known += u->empty() ? 0 : 1;
    if (known) {
        o.text("FIELD FieldData %d\n", known);
        for (int i = 0; i < 3; ++i) {
            if (units[i]->empty()) continue;
            o.text("%s 1 1 string\n", kUnitArrays[i]);
            if (opts.binary) {
                o.s += char(0xC0 | (units[i]->size() & 0x3f));
                o.s += *units[i];
            } else {
                for (unsigned char ch : *units[i]) {
                    if (ch > ' ' && ch < 0x7f && ch != '%') o.s += char(ch);
                    else o.text("%%%02X", unsigned(ch));
                }
            }
            o.s += '\n';
        }
    }
    o.text("POINTS %zu float\n", n);
    o.floats(reinterpret_cast<const float*>(pl.position.data()), n * 3, 9);
    size_t conn = 0;
    for (auto& r : pl.lines) conn += r.count;
    if (opts.version51) {
        o.text("LINES %zu %zu\nOFFSETS vtktypeint64\n", l + 1, conn);
        std::vector<int64_t> off{0};
        for (auto& r : pl.lines) off.push_back(off.back() + r.count);
        o.ints(off, true, 9);
        o.text("CONNECTIVITY vtktypeint64\n");
        std::vector<int64_t> c;
        c.reserve(conn);
        for (auto& r : pl.lines) for (uint32_t k = 0; k < r.count; ++k) c.push_back(r.first + k);
        o.ints(c, true, 9);
    } else {
        o.text("LINES %zu %zu\n", l, conn + l);
        std::vector<int64_t> cells;
        cells.reserve(conn + l);
        for (auto& r : pl.lines) {
            cells.push_back(r.count);
            for (uint32_t k = 0; k < r.count; ++k) cells.push_back(r.first + k);
        }
        o.ints(cells, false, 9);
    }
    o.text("POINT_DATA %zu\nSCALARS time float 1\nLOOKUP_TABLE default\n", n);
    o.floats(pl.time.data(), n, 9);
    o.text("VECTORS velocity float\n");
    o.floats(reinterpret_cast<const float*>(pl.velocity.data()), n * 3, 9);
    return std::move(o.s);
}

}  // namespace pathlet::io
