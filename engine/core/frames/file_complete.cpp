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

// Reads at positions within a file without reading the rest of it; every read is checked
// against the file's size (false: past the end, or the stream failed).
class FileReader {
public:
    explicit FileReader(const std::string& path) : in_(path, std::ios::binary | std::ios::ate) {
        size_ = in_ ? uint64_t(in_.tellg()) : 0;
    }
    uint64_t size() const { return size_; }
    bool read(uint64_t at, void* dst, size_t n) {
        if (!in_ || at + n > size_) return false;
        in_.seekg(std::streamoff(at));
        return bool(in_.read(static_cast<char*>(dst), std::streamsize(n)));
    }
    // Little-endian (or big-endian where `big`) unsigned of n <= 8 bytes.
    bool uint(uint64_t at, size_t n, uint64_t& v, bool big = false) {
        unsigned char b[8] = {};
        if (!read(at, b, n)) return false;
        v = 0;
        for (size_t i = 0; i < n; ++i) v |= uint64_t(b[big ? n - 1 - i : i]) << (8 * i);
        return true;
    }
    bool cstr(uint64_t& at, std::string& s) {  // a 0-terminated string of at most 255 bytes
        s.clear();
        for (char c = 0; s.size() < 256; ++at) {
            if (!read(at, &c, 1)) return false;
            if (c == 0) {
                ++at;
                return true;
            }
            s.push_back(c);
        }
        return false;
    }

private:
    std::ifstream in_;
    uint64_t size_ = 0;
};

bool png_complete(FileReader& f) {
    static const unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
    unsigned char tail[12] = {};
    return f.size() >= 12 && f.read(f.size() - 12, tail, 12) && std::memcmp(tail, iend, 12) == 0;
}

bool jpeg_complete(FileReader& f) {  // ends with the end-of-image marker
    unsigned char tail[2] = {};
    return f.size() >= 4 && f.read(f.size() - 2, tail, 2) && tail[0] == 0xFF && tail[1] == 0xD9;
}

// -1: not a layout this checks (tiled, multi-part, deep): the caller reads the file instead.
// Reads the header, the offset table and 8 bytes a chunk, not the pixels.
int exr_complete(FileReader& f) {
    uint64_t magic = 0, version = 0, at = 8;
    if (!f.uint(0, 4, magic) || magic != 20000630u || !f.uint(4, 4, version)) return 0;
    if (version & (0x200u | 0x800u | 0x1000u)) return -1;
    int64_t ymin = 0, ymax = -1;
    int lines_per_chunk = -1;
    for (;;) {  // the header's attributes, up to an empty name
        std::string name, type;
        uint64_t size = 0;
        if (!f.cstr(at, name)) return 0;
        if (name.empty()) break;
        if (!f.cstr(at, type) || !f.uint(at, 4, size) || at + 4 + size > f.size()) return 0;
        at += 4;
        if (name == "dataWindow" && size == 16) {
            uint64_t y0 = 0, y1 = 0;
            if (!f.uint(at + 4, 4, y0) || !f.uint(at + 12, 4, y1)) return 0;
            ymin = int32_t(uint32_t(y0));
            ymax = int32_t(uint32_t(y1));
        }
        if (name == "compression" && size == 1) {
            static const int lines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
            uint64_t c = 0;
            if (!f.uint(at, 1, c)) return 0;
            lines_per_chunk = c < 10 ? lines[c] : -1;
        }
        at += size;
    }
    if (lines_per_chunk < 0 || ymax < ymin) return -1;
    const uint64_t chunks = (uint64_t(ymax - ymin) + 1 + uint64_t(lines_per_chunk) - 1) / uint64_t(lines_per_chunk);
    const uint64_t table_end = at + chunks * 8;
    for (uint64_t k = 0; k < chunks; ++k) {
        uint64_t offset = 0, data = 0;
        if (!f.uint(at + 8 * k, 8, offset)) return 0;
        // A chunk starts after the table; its y and size, then its data, lie inside the file.
        if (offset < table_end || !f.uint(offset + 4, 4, data) || offset + 8 + data > f.size()) return 0;
    }
    return 1;
}

// -1: not a layout this checks (BigTIFF, no strips or tiles): the caller reads the file instead.
// The first directory (libtiff writes it after the pixels) and every strip or tile it names lie
// inside the file.
int tiff_complete(FileReader& f) {
    unsigned char order[2] = {};
    if (!f.read(0, order, 2)) return 0;
    const bool big = order[0] == 'M';
    uint64_t magic = 0, ifd = 0, entries = 0;
    if ((order[0] != 'I' && order[0] != 'M') || order[0] != order[1] || !f.uint(2, 2, magic, big)) return 0;
    if (magic == 43) return -1;
    if (magic != 42 || !f.uint(4, 4, ifd, big) || ifd < 8 || !f.uint(ifd, 2, entries, big)) return 0;
    struct Field {
        uint64_t count = 0, at = 0;  // where the values lie
        size_t bytes = 0;            // a value's
    } offsets, counts;
    for (uint64_t e = 0; e < entries; ++e) {
        const uint64_t at = ifd + 2 + 12 * e;
        uint64_t tag = 0, type = 0, n = 0;
        if (!f.uint(at, 2, tag, big) || !f.uint(at + 2, 2, type, big) || !f.uint(at + 4, 4, n, big)) return 0;
        const size_t bytes = type == 3 ? 2 : type == 4 ? 4 : 0;  // SHORT, LONG
        Field* field = tag == 273 || tag == 324 ? &offsets : tag == 279 || tag == 325 ? &counts : nullptr;
        if (!field) continue;
        if (!bytes) return -1;
        field->count = n;
        field->bytes = bytes;
        field->at = at + 8;
        if (n * bytes > 4 && !f.uint(at + 8, 4, field->at, big)) return 0;
    }
    if (offsets.count == 0 || offsets.count != counts.count) return -1;
    for (uint64_t k = 0; k < offsets.count; ++k) {
        uint64_t o = 0, n = 0;
        if (!f.uint(offsets.at + k * offsets.bytes, offsets.bytes, o, big) || !f.uint(counts.at + k * counts.bytes, counts.bytes, n, big))
            return 0;
        if (o + n > f.size()) return 0;
    }
    return 1;
}

}  // namespace

bool image_file_complete(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    FileReader f(path);
    if (ext == ".png") return png_complete(f);
    if (ext == ".jpg" || ext == ".jpeg") return jpeg_complete(f);
    const int known = ext == ".exr" ? exr_complete(f) : ext == ".tif" || ext == ".tiff" ? tiff_complete(f) : -1;
    if (known >= 0) return known == 1;
    try {  // a format (or layout) checked by decoding it
        read_image(path);
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace pathlet
