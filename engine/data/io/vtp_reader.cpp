// VTK XML PolyData (.vtp) reader: ascii, inline base64, appended raw/base64, zlib
// compression (UInt32/UInt64 headers), several Pieces. Raw appended data makes the file
// invalid XML, so the head before <AppendedData> is scanned as XML and the tail is read
// by offsets.
#include "base64.hpp"
#include "pathline_formats.hpp"
#include "vtk_values.hpp"
#include "xml_scan.hpp"
#include "util/input_limits.hpp"
#include "units.hpp"
#include "zlib_blocks.hpp"

#include <deque>
#include <map>

namespace pathlet::io {

namespace {

struct ArrayTag {
    XmlTag tag;
    std::string_view section;  // PointData, Points, Lines, ...
    std::string_view payload;  // character data (inline arrays)
    size_t payload_at = 0;
};

// Bytes of one binary array, from either raw bytes or base64 text.
class ByteSource {
public:
    ByteSource(std::string_view raw, size_t at) : raw_(raw), at_(at) {}
    ByteSource(Base64Reader b64, size_t at) : b64_(b64), is_b64_(true), at_(at) {}
    size_t max_remaining() const { return is_b64_ ? b64_.max_remaining() : raw_.size() - pos_; }
    // n bytes, or nullopt-like empty + false when the data end first.
    bool take(size_t n, std::string_view& out) {
        if (!is_b64_) {
            if (n > raw_.size() - pos_) return false;
            out = raw_.substr(pos_, n);
            pos_ += n;
            return true;
        }
        scratch_.emplace_back();
        if (!b64_.read(n, scratch_.back())) return false;
        out = scratch_.back();
        return true;
    }
    size_t at() const { return at_; }
    bool is_base64() const { return is_b64_; }
    const char* b64_error() const { return is_b64_ ? b64_.error() : ""; }

private:
    std::string_view raw_;
    Base64Reader b64_{std::string_view{}};
    bool is_b64_ = false;
    size_t at_;
    size_t pos_ = 0;
    std::deque<std::string> scratch_;  // keeps decoded views alive (deque: stable addresses)
};

struct VtpReader {
    VtpReader(std::string_view b, const std::string& f, LoadReport& r) : bytes(b), file(f), report(r) {}
    std::string_view bytes;
    const std::string& file;
    LoadReport& report;
    bool big_endian = false;
    int header_bytes = 4;
    bool zlib = false;
    std::string_view appended;  // after the '_' marker
    size_t appended_at = 0;
    bool appended_base64 = false;

    [[noreturn]] void fail(size_t at, const std::string& m) const { fail_at(file, at_byte(at), m); }

    uint64_t attr_count(const XmlTag& t, std::string_view key, uint64_t max = UINT32_MAX) const {
        auto v = t.attr(key, "0");
        int64_t n;
        if (!parse_number(v, n) || n < 0 || uint64_t(n) > max)
            fail(t.begin, "<" + std::string(t.name) + "> attribute " + std::string(key) + "=\"" + std::string(v) +
                              "\" is not a valid count");
        return uint64_t(n);
    }

    uint64_t header_uint(ByteSource& src, const std::string& what) {
        std::string_view b;
        if (!src.take(size_t(header_bytes), b))
            fail(src.at(), what + ": data end inside the binary header (file truncated?) " + src.b64_error());
        uint64_t v = 0;
        for (int i = 0; i < header_bytes; ++i) {
            int k = big_endian ? i : header_bytes - 1 - i;
            v = (v << 8) | (unsigned char)b[size_t(k)];
        }
        return v;
    }

    // The array's value bytes (file byte order), exactly `expected` of them.
    std::string_view binary_payload(ByteSource& src, uint64_t expected, const std::string& what, std::string& storage) {
        std::string_view out;
        if (!zlib) {
            uint64_t n = header_uint(src, what);
            if (n != expected)
                fail(src.at(), what + ": binary header declares " + std::to_string(n) + " bytes but the array needs " +
                                   std::to_string(expected) + " (counts disagree)");
            if (n > src.max_remaining() || !src.take(size_t(n), out))
                fail(src.at(), what + ": " + std::to_string(n) + " bytes declared but the data end first (file truncated?) " +
                                   src.b64_error());
            if (src.is_base64()) {  // decoded bytes live in src, which the caller does not keep
                storage.assign(out);
                return storage;
            }
            return out;
        }
        ZlibBlockHeader h;
        h.blocks = header_uint(src, what);
        h.block_size = header_uint(src, what);
        h.last_block_size = header_uint(src, what);
        if (h.blocks > src.max_remaining() / size_t(header_bytes))
            fail(src.at(), what + ": zlib header declares " + std::to_string(h.blocks) + " blocks, more than the file holds");
        if (h.blocks > 0 && (h.block_size == 0 || h.last_block_size > h.block_size))
            fail(src.at(), what + ": zlib header has block size " + std::to_string(h.block_size) + " and last block size " +
                               std::to_string(h.last_block_size));
        uint64_t csum = 0;
        for (uint64_t i = 0; i < h.blocks; ++i) {
            h.compressed.push_back(header_uint(src, what));
            csum += h.compressed.back();
        }
        // The declared size must agree with the array before anything is inflated.
        bool too_many = h.blocks > 0 && h.blocks - 1 > expected / h.block_size;  // also guards the multiplication
        if (too_many || h.uncompressed_size() != expected)
            fail(src.at(), what + ": zlib header declares " +
                               (too_many ? std::string("far more") : std::to_string(h.uncompressed_size())) +
                               " uncompressed bytes but the array needs " + std::to_string(expected) +
                               " (counts disagree, or a decompression bomb)");
        // zlib inflates at most ~1032:1: a header whose blocks claim more than their compressed
        // bytes can hold is refused before any allocation (a "many small blocks" bomb).
        if (std::string bad = zlib_blocks_implausible(h); !bad.empty()) fail(src.at(), what + ": " + bad);
        std::string_view blocks;
        if (csum > src.max_remaining() || !src.take(size_t(csum), blocks))
            fail(src.at(), what + ": compressed blocks (" + std::to_string(csum) + " bytes) run past the end of the data (file truncated?)");
        storage.resize(size_t(expected));
        std::string err = zlib_blocks_decode(h, blocks, storage.data());
        if (!err.empty()) fail(src.at(), what + ": " + err);
        return storage;
    }

    template <class T>
    std::vector<T> read_array(const ArrayTag& a, uint64_t tuples, int comps, const std::string& what) {
        const XmlTag& t = a.tag;
        auto type = xml_type(t.attr("type"));
        if (!type) fail(t.begin, what + ": unknown type=\"" + std::string(t.attr("type")) + "\"");
        uint64_t ncomp = attr_count(t, "NumberOfComponents", 1 << 16);
        if (!t.find("NumberOfComponents")) ncomp = 1;
        if (comps > 0 && ncomp != uint64_t(comps))
            fail(t.begin, what + " has " + std::to_string(ncomp) + " components, expected " + std::to_string(comps));
        uint64_t count = tuples * ncomp;
        auto fmt = t.attr("format", "ascii");
        std::vector<T> out;
        if (fmt == "ascii") {
            Cursor c(bytes, file, false);
            c.seek(a.payload_at);
            return read_values<T>(c, count, *type, false, big_endian, what.c_str());
        }
        if (count > bytes.size() / scalar_size(*type) + 1 && !zlib)
            fail(t.begin, what + ": declares " + std::to_string(count) + " values, more than the file can hold");
        uint64_t expected = count * scalar_size(*type);
        std::string storage;
        std::string_view data;
        if (fmt == "binary") {
            ByteSource src(Base64Reader(a.payload), a.payload_at);
            data = binary_payload(src, expected, what, storage);
        } else if (fmt == "appended") {
            if (appended.data() == nullptr) fail(t.begin, what + " is format=\"appended\" but the file has no <AppendedData>");
            uint64_t off = attr_count(t, "offset", UINT64_MAX / 2);
            if (off > appended.size()) fail(t.begin, what + ": offset " + std::to_string(off) + " lies beyond the appended data");
            if (appended_base64) {
                ByteSource src(Base64Reader(appended, size_t(off)), appended_at + off);
                data = binary_payload(src, expected, what, storage);
            } else {
                ByteSource src(appended.substr(size_t(off)), appended_at + off);
                data = binary_payload(src, expected, what, storage);
            }
        } else {
            fail(t.begin, what + ": unknown format=\"" + std::string(fmt) + "\"");
        }
        out.resize(count);
        if constexpr (std::is_same_v<T, float>) decode_floats(data.data(), count, *type, big_endian, out.data());
        else decode_ints(data.data(), count, *type, big_endian, out.data());
        return out;
    }

    // The bytes of a String array (VTK: each string's characters, then a NUL; in ascii as
    // decimal codes). Units are short: more than kMaxStringBytes is refused before reading.
    static constexpr uint64_t kMaxStringBytes = 4096;
    std::string string_bytes(const ArrayTag& a, const std::string& what) {
        const XmlTag& t = a.tag;
        auto fmt = t.attr("format", "ascii");
        std::string out;
        if (fmt == "ascii") {
            Cursor c(a.payload, file, false);  // the characters up to the closing tag
            for (auto tok = c.token(); !tok.empty(); tok = c.token()) {
                int64_t v;
                if (!parse_number(tok, v) || v < 0 || v > 255)
                    fail(a.payload_at, what + ": '" + std::string(tok.substr(0, 20)) + "' is not a character code");
                if (out.size() >= kMaxStringBytes) fail(a.payload_at, what + ": longer than " + std::to_string(kMaxStringBytes) + " bytes");
                out += char(v);
            }
            return out;
        }
        auto read_from = [&](ByteSource src) {
            // The size comes from the array's own header: peek at a copy, then read for real.
            ByteSource peek = src;
            uint64_t n = 0;
            if (!zlib) {
                n = header_uint(peek, what);
            } else {
                uint64_t blocks = header_uint(peek, what), block = header_uint(peek, what), last = header_uint(peek, what);
                if (blocks > kMaxStringBytes || block > kMaxStringBytes)
                    fail(src.at(), what + ": zlib header declares more than " + std::to_string(kMaxStringBytes) + " bytes");
                n = blocks == 0 ? 0 : (blocks - 1) * block + (last ? last : block);
            }
            if (n > kMaxStringBytes) fail(src.at(), what + ": declares " + std::to_string(n) + " bytes, more than a unit needs");
            std::string storage;
            return std::string(binary_payload(src, n, what, storage));
        };
        if (fmt == "binary") return read_from(ByteSource(Base64Reader(a.payload), a.payload_at));
        if (fmt == "appended") {
            if (appended.data() == nullptr) fail(t.begin, what + " is format=\"appended\" but the file has no <AppendedData>");
            uint64_t off = attr_count(t, "offset", UINT64_MAX / 2);
            if (off > appended.size()) fail(t.begin, what + ": offset " + std::to_string(off) + " lies beyond the appended data");
            return appended_base64 ? read_from(ByteSource(Base64Reader(appended, size_t(off)), appended_at + off))
                                   : read_from(ByteSource(appended.substr(size_t(off)), appended_at + off));
        }
        fail(t.begin, what + ": unknown format=\"" + std::string(fmt) + "\"");
    }

    // LengthUnit / TimeUnit / VelocityUnit among the dataset's field data (other arrays are
    // not read). A unit we cannot show is dropped with a warning, never an error.
    void read_units(const std::vector<ArrayTag>& field, Units& units) {
        for (auto& a : field) {
            const std::string name(a.tag.attr("Name"));
            const int which = unit_array_index(name);
            if (which < 0) continue;
            if (a.tag.attr("type") != "String") {
                report.warnings.push_back("field data '" + name + "' is not a String array: unit ignored");
                continue;
            }
            const std::string raw = string_bytes(a, "FieldData array '" + name + "'");
            const std::string unit = sanitize_unit(raw.substr(0, raw.find('\0')));
            if (unit.empty()) report.warnings.push_back("field data '" + name + "' holds no printable unit: ignored");
            else unit_slot(units, which) = unit;
        }
    }

    RawPolylines read_piece(const XmlTag& piece, const std::vector<ArrayTag>& arrays) {
        RawPolylines raw;
        uint64_t np = attr_count(piece, "NumberOfPoints"), nl = attr_count(piece, "NumberOfLines");
        raw.polygons = attr_count(piece, "NumberOfPolys") + attr_count(piece, "NumberOfStrips");
        raw.where_lines = raw.where_data = at_byte(piece.begin);
        const ArrayTag *points = nullptr, *conn = nullptr, *offs = nullptr;
        for (auto& a : arrays) {
            if (a.section == "Points" && !points) points = &a;
            if (a.section == "Lines" && a.tag.attr("Name") == "connectivity") conn = &a;
            if (a.section == "Lines" && a.tag.attr("Name") == "offsets") offs = &a;
        }
        if (np > 0 && !points) fail(piece.begin, "Piece has " + std::to_string(np) + " points but no <Points> array");
        if (points) {
            raw.where_data = at_byte(points->tag.begin);
            raw.points = read_array<float>(*points, np, 3, "Points");
            if (floats_look_garbled(raw.points.data(), raw.points.size()))
                fail(points->tag.begin, "Points hold absurd values (byte_order=\"" + std::string(big_endian ? "BigEndian" : "LittleEndian") +
                                            "\" wrong, or corrupt data)");
        }
        if (nl > 0) {
            if (!conn || !offs) fail(piece.begin, "Piece has " + std::to_string(nl) + " lines but <Lines> lacks connectivity/offsets");
            raw.where_lines = at_byte(offs->tag.begin);
            auto end_offsets = read_array<int64_t>(*offs, nl, 1, "Lines offsets");
            // XML offsets are end offsets without the leading 0.
            for (size_t i = 0; i < end_offsets.size(); ++i)
                if (end_offsets[i] < (i ? end_offsets[i - 1] : 0))
                    fail(offs->tag.begin, "Lines offsets are not monotone at entry " + std::to_string(i) + " (" +
                                              std::to_string(end_offsets[i]) + ")");
            uint64_t nconn = end_offsets.empty() ? 0 : uint64_t(end_offsets.back());
            if (nconn > bytes.size() * 8)
                fail(offs->tag.begin, "Lines offsets end at " + std::to_string(nconn) + ", more than the file can hold");
            raw.connectivity = read_array<int64_t>(*conn, nconn, 1, "Lines connectivity");
            raw.offsets.assign(1, 0);
            raw.offsets.insert(raw.offsets.end(), end_offsets.begin(), end_offsets.end());
        }
        for (auto& a : arrays) {
            if (a.section != "PointData") continue;
            std::string name(a.tag.attr("Name"));
            auto vals = read_array<float>(a, np, 0, "PointData array '" + name + "'");
            int comps = a.tag.find("NumberOfComponents") ? int(attr_count(a.tag, "NumberOfComponents")) : 1;
            raw.point_arrays.push_back({name, comps, std::move(vals)});
        }
        validate_topology(raw, file);
        return raw;
    }

    RawPolylines run() {
        size_t app = bytes.find("<AppendedData");
        std::string_view head = bytes.substr(0, app == std::string_view::npos ? bytes.size() : app);
        auto tags = scan_xml(head, file);
        const XmlTag* root = nullptr;
        for (auto& t : tags)
            if (t.name == "VTKFile" && !t.closing) { root = &t; break; }
        if (!root) fail(0, "no <VTKFile> element: not a VTK XML file");
        auto type = root->attr("type");
        if (type != "PolyData")
            fail(root->begin, "VTKFile type=\"" + std::string(type) + "\" is not supported: pathlines must be PolyData (.vtp)");
        big_endian = root->attr("byte_order", "LittleEndian") == "BigEndian";
        auto ht = root->attr("header_type", "UInt32");
        if (ht == "UInt64") header_bytes = 8;
        else if (ht != "UInt32") fail(root->begin, "header_type=\"" + std::string(ht) + "\" is not supported (UInt32 or UInt64)");
        auto comp = root->attr("compressor");
        if (comp == "vtkZLibDataCompressor") zlib = true;
        else if (!comp.empty())
            fail(root->begin, "compressor \"" + std::string(comp) + "\" is not supported; only vtkZLibDataCompressor. "
                              "Re-save the file uncompressed or with zlib (ParaView: Save Data > Compressor Type > ZLib)");
        report.format = "VTK XML PolyData " + std::string(root->attr("version", "?"));

        std::string enc_name = "ascii";
        if (app != std::string_view::npos) {
            XmlTag at = parse_xml_tag(bytes, app, file);
            auto enc = at.attr("encoding", "raw");
            appended_base64 = enc == "base64";
            if (!appended_base64 && enc != "raw") fail(app, "AppendedData encoding=\"" + std::string(enc) + "\" is not supported");
            size_t u = bytes.find('_', at.end);
            if (u == std::string_view::npos) fail(at.end, "AppendedData has no '_' marker (file truncated?)");
            appended_at = u + 1;
            appended = bytes.substr(appended_at);
            if (appended_base64) {
                size_t close = appended.find('<');
                if (close != std::string_view::npos) appended = appended.substr(0, close);
            }
        }

        RawPolylines all;
        std::vector<std::string_view> stack;
        const XmlTag* piece = nullptr;
        std::vector<ArrayTag> arrays, field;
        int pieces = 0;
        std::map<std::string, int> formats;
        for (auto& t : tags) {
            if (t.closing) {
                if (t.name == "Piece" && piece) {
                    append_piece(all, read_piece(*piece, arrays), report);
                    piece = nullptr;
                    arrays.clear();
                }
                if (!stack.empty()) stack.pop_back();
                continue;
            }
            if (t.name == "Piece") {
                if (stack.empty() || stack.back() != "PolyData") fail(t.begin, "<Piece> outside <PolyData>");
                piece = &t;
                ++pieces;
            } else if (t.name == "DataArray" && !stack.empty() && (piece || stack.back() == "FieldData")) {
                ArrayTag a{t, stack.back(), {}, t.end};
                if (!t.self_closing) {
                    size_t e = head.find('<', t.end);
                    a.payload = head.substr(t.end, (e == std::string_view::npos ? head.size() : e) - t.end);
                }
                if (piece) {
                    formats[std::string(t.attr("format", "ascii"))]++;
                    arrays.push_back(a);
                } else {
                    field.push_back(a);
                }
            }
            if (!t.self_closing) stack.push_back(t.name);
            else if (t.name == "Piece") {
                append_piece(all, read_piece(t, {}), report);
                piece = nullptr;
            }
        }
        if (piece) fail(piece->begin, "<Piece> is not closed (file truncated?)");
        read_units(field, all.units);
        std::string fmts;
        for (auto& [k, v] : formats) fmts += (fmts.empty() ? "" : "+") + k;
        if (fmts == "appended") fmts += appended_base64 ? " base64" : " raw";
        report.format += ", " + (fmts.empty() ? std::string("empty") : fmts) + (zlib ? ", zlib" : "") + ", " +
                         std::string(ht) + " headers, " + (big_endian ? "big-endian" : "little-endian");
        if (pieces > 1) report.format += ", " + std::to_string(pieces) + " pieces";
        return all;
    }
};

}  // namespace

RawPolylines read_vtp(std::string_view bytes, const std::string& file, LoadReport& report) {
    return VtpReader(bytes, file, report).run();
}

}  // namespace pathlet::io
