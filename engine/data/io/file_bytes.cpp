#include "file_bytes.hpp"

#include "byte_reader.hpp"
#include "native_cache.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

namespace pathlet::io {

std::string read_file_bytes(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) fail_at(path, at_byte(0), "is a directory, expected a file");
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) fail_at(path, at_byte(0), std::string("cannot open: ") + std::strerror(errno));
    std::string out;
    if (std::fseek(f.get(), 0, SEEK_END) == 0) {
        long n = std::ftell(f.get());
        if (n > 0) {
            std::fseek(f.get(), 0, SEEK_SET);
            out.resize(size_t(n));
            size_t got = std::fread(out.data(), 1, out.size(), f.get());
            out.resize(got);
            return out;
        }
        std::fseek(f.get(), 0, SEEK_SET);
    }
    char buf[1 << 16];  // pipes and special files: size unknown
    size_t got;
    while ((got = std::fread(buf, 1, sizeof buf, f.get())) > 0) out.append(buf, got);
    // No format is empty: a 0-byte file is a failed download or copy, never an empty data set.
    if (out.empty()) fail_at(path, at_byte(0), "the file is empty (0 bytes)");
    return out;
}

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (auto& c : ext) c = char(std::tolower((unsigned char)c));
    return ext;
}

static bool starts_with_ci(std::string_view s, std::string_view prefix) {
    return s.size() >= prefix.size() && iequals(s.substr(0, prefix.size()), prefix);
}

Sniffed sniff(std::string_view b, const std::string& path) {
    std::string ext = lower_extension(path);
    if (b.size() >= kNativeMagic.size() && b.substr(0, kNativeMagic.size()) == kNativeMagic) return Sniffed::Native;
    if (b.size() >= 4 && b.substr(0, 4) == "glTF") return Sniffed::Glb;
    // Tractography: TrackVis's magic "TRACK\0", MRtrix's first line (a .trk/.tck file without
    // them still goes to its reader below, which says what is wrong).
    if (b.substr(0, 6) == std::string_view("TRACK\0", 6)) return Sniffed::TrackVis;
    if (b.substr(0, 13) == "mrtrix tracks") return Sniffed::MrtrixTck;
    // Binary STL: 80-byte header, uint32 count, 50 bytes per triangle; the size rule wins
    // over a header that happens to start with "solid" (many exporters do that).
    if (b.size() >= 84) {
        uint32_t n;
        std::memcpy(&n, b.data() + 80, 4);
        if (uint64_t(84) + uint64_t(n) * 50 == b.size()) return Sniffed::StlBinary;
    }
    size_t i = 0;
    if (b.size() >= 3 && (unsigned char)b[0] == 0xEF && (unsigned char)b[1] == 0xBB && (unsigned char)b[2] == 0xBF) i = 3;
    while (i < b.size() && is_space(b[i])) ++i;
    std::string_view s = b.substr(i);
    if (starts_with_ci(s, "# vtk DataFile")) return Sniffed::VtkLegacy;
    if (s.substr(0, 200).find("<VTKFile") != std::string_view::npos) return Sniffed::VtkXml;
    if (!s.empty() && s[0] == '<') return ext == ".vtp" ? Sniffed::VtkXml : Sniffed::Unknown;
    if (!s.empty() && s[0] == '{') return Sniffed::Gltf;
    if (starts_with_ci(s, "solid") && s.substr(0, 4096).find("facet") != std::string_view::npos) return Sniffed::StlAscii;
    if (ext == ".trk") return Sniffed::TrackVis;
    if (ext == ".tck") return Sniffed::MrtrixTck;
    if (ext == ".stl") return b.size() >= 84 ? Sniffed::StlBinary : Sniffed::StlAscii;
    if (ext == ".obj") return Sniffed::Obj;
    if (ext == ".gltf") return Sniffed::Gltf;
    // OBJ: lines starting with v/vn/f/#/o/g/mtllib...
    if (!s.empty() && (s[0] == '#' || s.substr(0, 2) == "v " || s.substr(0, 2) == "o " || s.substr(0, 2) == "g " ||
                       s.substr(0, 6) == "mtllib"))
        return Sniffed::Obj;
    if (!s.empty() && (std::isdigit((unsigned char)s[0]) || s[0] == '-' || s[0] == '+' || s[0] == '.'))
        return Sniffed::TextRows;
    if (s.empty()) return ext == ".vtk" ? Sniffed::VtkLegacy : ext == ".vtp" ? Sniffed::VtkXml : Sniffed::TextRows;
    return Sniffed::Unknown;
}

const char* sniffed_name(Sniffed s) {
    switch (s) {
        case Sniffed::VtkLegacy: return "VTK legacy";
        case Sniffed::VtkXml: return "VTK XML";
        case Sniffed::Native: return "pathlet native cache";
        case Sniffed::Gltf: return "glTF";
        case Sniffed::Glb: return "glTF binary";
        case Sniffed::StlAscii: return "STL ascii";
        case Sniffed::StlBinary: return "STL binary";
        case Sniffed::Obj: return "Wavefront OBJ";
        case Sniffed::TextRows: return "plain-text pathline rows";
        case Sniffed::TrackVis: return "TrackVis .trk";
        case Sniffed::MrtrixTck: return "MRtrix .tck";
        default: return "unknown";
    }
}

}  // namespace pathlet::io
