// VTK XML ImageData (.vti) reader for velocity volumes: point-data arrays in ascii,
// inline base64 (optionally zlib) or appended (raw or base64) form.
#include "field_readers.hpp"
#include "vti_codec.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <map>
#include <optional>
#include <sstream>

namespace pathlet::trace {
namespace {

struct Tag {
    std::string name;
    std::map<std::string, std::string> attr;
    size_t begin = 0, end = 0;  // byte range of "<...>"
};

[[noreturn]] void fail(const std::string& path, size_t at, const std::string& what) {
    throw DataError(path + ": byte " + std::to_string(at) + ": " + what);
}

// Next tag named `name` at or after `from` within [0, limit); nullopt when absent.
std::optional<Tag> find_tag(std::string_view x, const std::string& name, size_t from, size_t limit, const std::string& path) {
    for (size_t at = x.find("<" + name, from); at < limit && at != std::string_view::npos; at = x.find("<" + name, at + 1)) {
        const char after = at + 1 + name.size() < x.size() ? x[at + 1 + name.size()] : '>';
        if (!(after == ' ' || after == '>' || after == '/' || after == '\n' || after == '\t' || after == '\r')) continue;
        const size_t close = x.find('>', at);
        if (close == std::string_view::npos) fail(path, at, "unterminated <" + name + ">");
        Tag t{name, {}, at, close + 1};
        const std::string_view body = x.substr(at + 1 + name.size(), close - at - 1 - name.size());
        for (size_t p = 0; p < body.size();) {
            const size_t eq = body.find('=', p);
            if (eq == std::string_view::npos) break;
            size_t k0 = p;
            while (k0 < eq && std::isspace(static_cast<unsigned char>(body[k0]))) ++k0;
            const size_t q0 = body.find('"', eq);
            const size_t q1 = q0 == std::string_view::npos ? q0 : body.find('"', q0 + 1);
            if (q1 == std::string_view::npos) fail(path, at, "bad attribute in <" + name + ">");
            std::string key(body.substr(k0, eq - k0));
            key.erase(std::remove_if(key.begin(), key.end(), ::isspace), key.end());
            t.attr[key] = std::string(body.substr(q0 + 1, q1 - q0 - 1));
            p = q1 + 1;
        }
        return t;
    }
    return std::nullopt;
}

std::string attr(const Tag& t, const std::string& key, const std::string& def = "") {
    const auto it = t.attr.find(key);
    return it == t.attr.end() ? def : it->second;
}

std::vector<double> numbers(const std::string& s) {
    std::vector<double> v;
    std::istringstream in(s);
    for (double d; in >> d;) v.push_back(d);
    return v;
}

size_t type_size(const std::string& t) {
    if (t == "Int8" || t == "UInt8") return 1;
    if (t == "Int16" || t == "UInt16") return 2;
    if (t == "Int32" || t == "UInt32" || t == "Float32") return 4;
    if (t == "Int64" || t == "UInt64" || t == "Float64") return 8;
    return 0;
}

float decode(const char* p, const std::string& t, bool big_endian) {
    const size_t n = type_size(t);
    uint64_t u = 0;
    for (size_t i = 0; i < n; ++i) {
        const uint8_t byte = uint8_t(p[big_endian ? i : n - 1 - i]);
        u = (u << 8) | byte;
    }
    if (t == "Float32") { uint32_t w = uint32_t(u); float f; std::memcpy(&f, &w, 4); return f; }
    if (t == "Float64") { double d; std::memcpy(&d, &u, 8); return float(d); }
    if (t == "Int8") return float(int8_t(u));
    if (t == "Int16") return float(int16_t(u));
    if (t == "Int32") return float(int32_t(u));
    if (t == "Int64") return float(int64_t(u));
    return float(u);
}

struct Array {
    std::string name;
    int comps = 1;
    std::vector<float> values;
};

// How the file stores its arrays: byte order, block header size, zlib, and where the appended
// section starts (npos: none) and whether it is base64.
struct Encoding {
    bool big = false;
    size_t header_size = 4;
    bool zlib = false;
    size_t base = std::string_view::npos;
    bool appended_b64 = false;
};

// The values of one <DataArray> of a grid of n points (ascii, inline binary or appended).
Array read_data_array(std::string_view x, const Tag& da, const Encoding& enc, size_t n, const std::string& path) {
    Array a;
    a.name = attr(da, "Name");
    a.comps = std::max(1, std::atoi(attr(da, "NumberOfComponents", "1").c_str()));
    const std::string type = attr(da, "type"), format = attr(da, "format", "ascii");
    const size_t ts = type_size(type);
    if (ts == 0) fail(path, da.begin, "array '" + a.name + "': unsupported type '" + type + "'");
    const size_t count = n * size_t(a.comps);
    if (count > x.size() * 1100 / ts + 16) fail(path, da.begin, "array '" + a.name + "': declared size exceeds what the file can hold");
    const size_t limit = std::min<size_t>(count * ts, x.size() * 1100 + 1024);
    std::string bytes;
    try {
        if (format == "ascii") {
            const size_t close = x.find("</DataArray>", da.end);
            const auto v = numbers(std::string(x.substr(da.end, close - da.end)));
            if (v.size() < count) fail(path, da.end, "array '" + a.name + "': " + std::to_string(v.size()) + " values, expected " + std::to_string(count));
            a.values.assign(v.begin(), v.begin() + std::ptrdiff_t(count));
        } else if (format == "binary") {
            const size_t close = x.find("</DataArray>", da.end);
            const std::string raw = vti::base64_decode(x.substr(da.end, close - da.end));
            bytes = vti::decode_block(raw, enc.header_size, enc.zlib, limit).bytes;
        } else if (format == "appended") {
            if (enc.base == std::string_view::npos) fail(path, da.begin, "appended array but no <AppendedData>");
            const long long off_signed = std::atoll(attr(da, "offset").c_str());
            if (off_signed < 0) fail(path, da.begin, "array '" + a.name + "': negative offset");
            const size_t off = size_t(off_signed);
            if (off > x.size() - enc.base) fail(path, da.begin, "array '" + a.name + "': offset past the end of the file");
            std::string_view rest = x.substr(enc.base + off);
            if (enc.appended_b64) rest = rest.substr(0, rest.find("</AppendedData>"));  // text, so safe to search
            bytes = enc.appended_b64 ? vti::decode_block(vti::base64_decode(rest), enc.header_size, enc.zlib, limit).bytes
                                     : vti::decode_block(rest, enc.header_size, enc.zlib, limit).bytes;
        } else {
            fail(path, da.begin, "array '" + a.name + "': unknown format '" + format + "'");
        }
    } catch (const std::runtime_error& e) {
        if (dynamic_cast<const DataError*>(&e)) throw;
        fail(path, da.begin, "array '" + a.name + "': " + e.what());
    }
    if (a.values.empty()) {
        if (bytes.size() < count * ts) fail(path, da.begin, "array '" + a.name + "': " + std::to_string(bytes.size()) + " bytes, expected " + std::to_string(count * ts));
        a.values.resize(count);
        for (size_t i = 0; i < count; ++i) a.values[i] = decode(bytes.data() + i * ts, type, enc.big);
    }
    return a;
}

}  // namespace

VelocityField read_vti_field(std::string_view x, const std::string& path) {
    const size_t appended_at = std::min(x.find("<AppendedData"), x.size());
    const auto file = find_tag(x, "VTKFile", 0, appended_at, path);
    if (!file) fail(path, 0, "not a VTK XML file");
    if (file->attr.count("type") && file->attr.at("type") != "ImageData")
        fail(path, file->begin, "VTK XML type " + file->attr.at("type") + " is not ImageData");
    Encoding enc;
    enc.big = file->attr.count("byte_order") && file->attr.at("byte_order") == "BigEndian";
    enc.header_size = file->attr.count("header_type") && file->attr.at("header_type") == "UInt64" ? 8 : 4;
    enc.zlib = file->attr.count("compressor") && !file->attr.at("compressor").empty();
    if (enc.zlib && file->attr.at("compressor") != "vtkZLibDataCompressor")
        fail(path, file->begin, "unsupported compressor " + file->attr.at("compressor"));

    const auto image = find_tag(x, "ImageData", file->end, appended_at, path);
    if (!image) fail(path, file->end, "no <ImageData>");
    VelocityField f;
    f.source = path;
    const auto ext = numbers(attr(*image, "WholeExtent"));
    if (ext.size() != 6) fail(path, image->begin, "WholeExtent needs 6 numbers");
    for (int a = 0; a < 3; ++a) {
        const double d = ext[2 * a + 1] - ext[2 * a] + 1;
        if (d < 1 || d > 100000) fail(path, image->begin, "bad WholeExtent");
        f.grid.dims[a] = int(d);
    }
    const auto org = numbers(attr(*image, "Origin", "0 0 0"));
    const auto sp = numbers(attr(*image, "Spacing", "1 1 1"));
    if (org.size() != 3 || sp.size() != 3) fail(path, image->begin, "Origin and Spacing need 3 numbers");
    for (int a = 0; a < 3; ++a) {
        f.grid.spacing[a] = float(sp[a]);
        f.grid.origin[a] = float(org[a] + ext[2 * a] * sp[a]);  // extents may start off zero
    }
    const size_t n = f.grid.count();

    // Appended section: offsets count from just after the '_'.
    if (appended_at < x.size()) {
        const auto app = find_tag(x, "AppendedData", appended_at, x.size(), path);
        if (!app) fail(path, appended_at, "'<AppendedData' is not a complete <AppendedData ...> tag");
        enc.appended_b64 = attr(*app, "encoding") == "base64";
        enc.base = x.find('_', app->end);
        if (enc.base == std::string_view::npos) fail(path, app->end, "no '_' starting the appended data");
        ++enc.base;
    }

    const auto pd = find_tag(x, "PointData", image->end, appended_at, path);
    if (!pd) fail(path, image->end, "no <PointData>");
    const size_t pd_end = std::min(x.find("</PointData>", pd->end), appended_at);
    std::vector<Array> arrays;
    for (auto da = find_tag(x, "DataArray", pd->end, pd_end, path); da; da = find_tag(x, "DataArray", da->end, pd_end, path))
        arrays.push_back(read_data_array(x, *da, enc, n, path));

    // Velocity: the PointData "Vectors" array, else the first 3-component one.
    auto lower = [](std::string s) { std::transform(s.begin(), s.end(), s.begin(), ::tolower); return s; };
    const Array* vel = nullptr;
    const Array* scal = nullptr;
    const Array* mask = nullptr;
    for (const auto& a : arrays) {
        if (a.comps == 3 && (!vel || (a.name == attr(*pd, "Vectors") && vel->name != a.name))) vel = &a;
        if (a.comps == 1 && lower(a.name) == "mask") mask = &a;
        else if (a.comps == 1 && (!scal || a.name == attr(*pd, "Scalars"))) scal = &a;
    }
    if (!vel) fail(path, pd->begin, "no 3-component point array (velocity)");
    f.frames.assign(1, std::vector<glm::vec3>(n));
    for (size_t i = 0; i < n; ++i) f.frames[0][i] = {vel->values[3 * i], vel->values[3 * i + 1], vel->values[3 * i + 2]};
    f.frame_times = {0.0f};
    if (mask) f.mask = mask->values;
    if (scal) f.scalars = scal->values, f.scalars_name = scal->name;
    f.check();
    return f;
}

}  // namespace pathlet::trace
