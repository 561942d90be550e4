#include "frames/file_complete.hpp"

#include "image_io.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

namespace fs = std::filesystem;

namespace pathlet {

namespace {

std::vector<unsigned char> slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool png_complete(const std::string& path) {
    static const unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    unsigned char tail[12] = {};
    return in && in.tellg() >= 12 && in.seekg(-12, std::ios::end) && in.read(reinterpret_cast<char*>(tail), 12) &&
           std::memcmp(tail, iend, 12) == 0;
}

// Little-endian reads within the file; false when past its end.
struct Reader {
    const std::vector<unsigned char>& b;
    size_t at = 0;
    bool u32(uint32_t& v) {
        if (at + 4 > b.size()) return false;
        v = uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
        at += 4;
        return true;
    }
    bool u64(uint64_t& v) {
        uint32_t lo = 0, hi = 0;
        if (!u32(lo) || !u32(hi)) return false;
        v = uint64_t(hi) << 32 | lo;
        return true;
    }
    bool cstr(std::string& s) {
        const auto end = std::find(b.begin() + long(at), b.end(), 0);
        if (end == b.end()) return false;
        s.assign(b.begin() + long(at), end);
        at = size_t(end - b.begin()) + 1;
        return true;
    }
};

// -1: not a layout this checks (tiled, multi-part, deep): the caller reads the file instead.
int exr_complete(const std::string& path) {
    const std::vector<unsigned char> b = slurp(path);
    Reader r{b};
    uint32_t magic = 0, version = 0;
    if (!r.u32(magic) || magic != 20000630u || !r.u32(version)) return 0;
    if (version & (0x200u | 0x800u | 0x1000u)) return -1;
    int32_t ymin = 0, ymax = -1;
    int lines_per_chunk = -1;
    for (;;) {  // the header's attributes, up to an empty name
        std::string name, type;
        uint32_t size = 0;
        if (!r.cstr(name)) return 0;
        if (name.empty()) break;
        if (!r.cstr(type) || !r.u32(size) || r.at + size > b.size()) return 0;
        if (name == "dataWindow" && size == 16) {
            uint32_t v[4] = {};
            for (uint32_t& x : v) r.u32(x);  // inside the file: checked above
            ymin = int32_t(v[1]);
            ymax = int32_t(v[3]);
            continue;
        }
        if (name == "compression" && size == 1) {
            static const int lines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
            lines_per_chunk = b[r.at] < 10 ? lines[b[r.at]] : -1;
        }
        r.at += size;
    }
    if (lines_per_chunk < 0 || ymax < ymin) return -1;
    const uint64_t chunks = (uint64_t(ymax - ymin) + 1 + uint64_t(lines_per_chunk) - 1) / uint64_t(lines_per_chunk);
    const uint64_t table_end = r.at + chunks * 8;
    for (uint64_t k = 0; k < chunks; ++k) {
        uint64_t offset = 0;
        if (!r.u64(offset)) return 0;
        // A chunk starts after the table; its y and size, then its data, lie inside the file.
        if (offset < table_end || offset + 8 > b.size()) return 0;
        Reader c{b, size_t(offset) + 4};
        uint32_t data = 0;
        if (!c.u32(data) || c.at + data > b.size()) return 0;
    }
    return 1;
}

}  // namespace

bool image_file_complete(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    if (ext == ".png") return png_complete(path);
    if (ext == ".exr") {
        const int whole = exr_complete(path);
        if (whole >= 0) return whole == 1;
    }
    try {
        read_image(path);
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace pathlet
