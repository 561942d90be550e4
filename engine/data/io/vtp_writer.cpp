// VTK XML PolyData writer in every encoding the reader accepts (see VtpWriteOptions).
#include "base64.hpp"
#include "pathline_formats.hpp"
#include "units.hpp"
#include "zlib_blocks.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>

namespace pathlet::io {

namespace {

using Enc = VtpWriteOptions::Encoding;

struct Writer {
    const VtpWriteOptions& o;
    std::string xml, appended;  // appended: raw bytes, or base64 text

    std::string uint_bytes(uint64_t v) const {
        std::string s;
        int n = o.header64 ? 8 : 4;
        for (int i = 0; i < n; ++i) s += char((v >> (8 * (o.big_endian ? n - 1 - i : i))) & 0xFF);
        return s;
    }
    // Values in file byte order.
    template <class T>
    std::string value_bytes(const T* v, size_t n) const {
        std::string s(n * sizeof(T), '\0');
        if (n) std::memcpy(s.data(), v, s.size());
        if (o.big_endian != (std::endian::native == std::endian::big))
            for (size_t i = 0; i < n; ++i) std::reverse(s.begin() + i * sizeof(T), s.begin() + (i + 1) * sizeof(T));
        return s;
    }
    // Header + data, as VTK lays out a binary array.
    std::pair<std::string, std::string> blob(const std::string& data) const {
        if (o.zlib) {
            std::string all = zlib_blocks_encode(data, o.header64 ? 8 : 4, o.big_endian, o.block_size);
            size_t nb = (data.size() + o.block_size - 1) / o.block_size;
            size_t hlen = (3 + nb) * (o.header64 ? 8 : 4);
            return {all.substr(0, hlen), all.substr(hlen)};
        }
        return {uint_bytes(data.size()), data};
    }
    std::string encode64(const std::pair<std::string, std::string>& b) const {
        // VTK encodes the zlib header separately; uncompressed header+data as one stream
        // unless asked otherwise (the reader must take both).
        if (o.zlib || o.separate_header_chunk) return base64_encode(b.first) + base64_encode(b.second);
        return base64_encode(b.first + b.second);
    }

    template <class T>
    void array(const char* type, const char* name, int comps, const T* v, size_t n_values, int indent) {
        std::string pad(size_t(indent), ' ');
        char head[256];
        std::snprintf(head, sizeof head, "%s<DataArray type=\"%s\" Name=\"%s\"%s", pad.c_str(), type, name,
                      comps > 1 ? (std::string(" NumberOfComponents=\"") + std::to_string(comps) + "\"").c_str() : "");
        xml += head;
        if (o.encoding == Enc::Ascii) {
            xml += " format=\"ascii\">\n" + pad + "  ";
            char buf[32];
            for (size_t i = 0; i < n_values; ++i) {
                int k = std::is_floating_point_v<T> ? std::snprintf(buf, sizeof buf, "%.9g", double(v[i]))
                                                    : std::snprintf(buf, sizeof buf, "%lld", (long long)v[i]);
                xml.append(buf, size_t(k));
                xml += (i + 1) % 9 == 0 && i + 1 < n_values ? "\n  " + pad : " ";
            }
            xml += "\n" + pad + "</DataArray>\n";
            return;
        }
        auto b = blob(value_bytes(v, n_values));
        if (o.encoding == Enc::Inline) {
            xml += " format=\"binary\">\n" + pad + "  " + encode64(b) + "\n" + pad + "</DataArray>\n";
            return;
        }
        xml += " format=\"appended\" offset=\"" + std::to_string(appended.size()) + "\"/>\n";
        appended += o.encoding == Enc::AppendedBase64 ? encode64(b) : b.first + b.second;
    }
};

}  // namespace

std::string write_vtp(const Pathlines& pl, const VtpWriteOptions& o) {
    Writer w{o, {}, {}};
    w.xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"";
    w.xml += o.big_endian ? "BigEndian" : "LittleEndian";
    w.xml += std::string("\" header_type=\"") + (o.header64 ? "UInt64" : "UInt32") + "\"";
    if (o.zlib) w.xml += " compressor=\"vtkZLibDataCompressor\"";
    w.xml += ">\n  <PolyData>\n";
    // Known units as field data String arrays (ascii: character codes, each string ends in 0).
    const std::string* units[3] = {&pl.units.length, &pl.units.time, &pl.units.velocity};
    if (!pl.units.length.empty() || !pl.units.time.empty() || !pl.units.velocity.empty()) {
        w.xml += "    <FieldData>\n";
        for (int i = 0; i < 3; ++i) {
            if (units[i]->empty()) continue;
            w.xml += std::string("      <DataArray type=\"String\" Name=\"") + kUnitArrays[i] +
                     "\" NumberOfTuples=\"1\" format=\"ascii\">\n        ";
            for (unsigned char c : *units[i]) w.xml += std::to_string(int(c)) + " ";
            w.xml += "0\n      </DataArray>\n";
        }
        w.xml += "    </FieldData>\n";
    }
    const size_t nl = pl.lines.size();
    const size_t pieces = std::max<size_t>(1, std::min<size_t>(size_t(std::max(o.pieces, 1)), std::max<size_t>(nl, 1)));
    for (size_t p = 0; p < pieces; ++p) {
        size_t l0 = nl * p / pieces, l1 = nl * (p + 1) / pieces;
        // Each piece stores its own lines' points contiguously.
        std::vector<float> pos, time, vel;
        std::vector<int64_t> conn, offs;
        for (size_t l = l0; l < l1; ++l) {
            auto r = pl.lines[l];
            for (uint32_t k = r.first; k < r.first + r.count; ++k) {
                conn.push_back(int64_t(pos.size() / 3));
                pos.insert(pos.end(), {pl.position[k].x, pl.position[k].y, pl.position[k].z});
                time.push_back(pl.time[k]);
                vel.insert(vel.end(), {pl.velocity[k].x, pl.velocity[k].y, pl.velocity[k].z});
            }
            offs.push_back(int64_t(conn.size()));
        }
        w.xml += "    <Piece NumberOfPoints=\"" + std::to_string(time.size()) + "\" NumberOfVerts=\"0\" NumberOfLines=\"" +
                 std::to_string(l1 - l0) + "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";
        w.xml += "      <PointData Scalars=\"time\" Vectors=\"velocity\">\n";
        w.array("Float32", "time", 1, time.data(), time.size(), 8);
        w.array("Float32", "velocity", 3, vel.data(), vel.size(), 8);
        w.xml += "      </PointData>\n      <Points>\n";
        w.array("Float32", "Points", 3, pos.data(), pos.size(), 8);
        w.xml += "      </Points>\n      <Lines>\n";
        w.array("Int64", "connectivity", 1, conn.data(), conn.size(), 8);
        w.array("Int64", "offsets", 1, offs.data(), offs.size(), 8);
        w.xml += "      </Lines>\n    </Piece>\n";
    }
    w.xml += "  </PolyData>\n";
    if (o.encoding == Enc::AppendedRaw || o.encoding == Enc::AppendedBase64) {
        w.xml += std::string("  <AppendedData encoding=\"") + (o.encoding == Enc::AppendedRaw ? "raw" : "base64") + "\">\n   _";
        w.xml += w.appended;
        w.xml += "\n  </AppendedData>\n";
    }
    w.xml += "</VTKFile>\n";
    return std::move(w.xml);
}

}  // namespace pathlet::io
