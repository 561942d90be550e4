#include "vti_codec.hpp"

#include <zlib.h>

#include <algorithm>
#include <stdexcept>

namespace pathlet::trace::vti {

std::string base64_decode(std::string_view text, size_t max_bytes) {
    auto val = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        if (c == '+') return 62;
        if (c == '/') return 63;
        if (c == '=') return -2;
        return -1;
    };
    std::string out;
    int group[4], n = 0;
    for (char ch : text) {
        if (out.size() >= max_bytes) break;
        const int v = val(ch);
        if (v == -1) {
            if (ch == ' ' || ch == '\n' || ch == '\r' || ch == '\t') continue;
            throw std::runtime_error("bad base64 character");
        }
        group[n++] = v;
        if (n < 4) continue;
        n = 0;
        if (group[0] < 0 || group[1] < 0) throw std::runtime_error("bad base64 padding");
        const uint32_t a = uint32_t(group[0]) << 18 | uint32_t(group[1]) << 12 | uint32_t(std::max(group[2], 0)) << 6 |
                           uint32_t(std::max(group[3], 0));
        out.push_back(char(a >> 16));
        if (group[2] >= 0) out.push_back(char(a >> 8));
        if (group[2] >= 0 && group[3] >= 0) out.push_back(char(a));
    }
    if (out.size() > max_bytes) out.resize(max_bytes);
    return out;
}

static uint64_t read_uint(std::string_view in, size_t at, size_t size) {
    if (at + size > in.size()) throw std::runtime_error("truncated size header");
    uint64_t v = 0;
    for (size_t i = 0; i < size; ++i) v |= uint64_t(uint8_t(in[at + i])) << (8 * i);  // little-endian
    return v;
}

Payload decode_block(std::string_view in, size_t hs, bool zlib, size_t limit) {
    Payload p;
    if (!zlib) {
        const uint64_t n = read_uint(in, 0, hs);
        if (n > limit || n > in.size() - hs) throw std::runtime_error("declared " + std::to_string(n) + " bytes, more than the file holds");
        p.bytes.assign(in.substr(hs, size_t(n)));
        p.consumed = hs + size_t(n);
        return p;
    }
    // [nblocks][block size][last block size][compressed size x nblocks][compressed data]
    const uint64_t nb = read_uint(in, 0, hs), bs = read_uint(in, hs, hs), last = read_uint(in, 2 * hs, hs);
    if (nb > in.size() / hs) throw std::runtime_error("block count larger than the file");
    const uint64_t total = nb == 0 ? 0 : (nb - 1) * bs + (last ? last : bs);
    if (total > limit) throw std::runtime_error("declared " + std::to_string(total) + " uncompressed bytes, too large");
    size_t at = 3 * hs + size_t(nb) * hs;
    if (at > in.size()) throw std::runtime_error("truncated block header");
    p.bytes.resize(size_t(total));
    size_t out_at = 0;
    for (uint64_t b = 0; b < nb; ++b) {
        const uint64_t cs = read_uint(in, 3 * hs + size_t(b) * hs, hs);
        if (cs > in.size() - at) throw std::runtime_error("compressed block runs past the end of the file");
        uLongf want = uLongf(b + 1 == nb && last ? last : bs);
        if (uncompress(reinterpret_cast<Bytef*>(p.bytes.data() + out_at), &want,
                       reinterpret_cast<const Bytef*>(in.data() + at), uLong(cs)) != Z_OK)
            throw std::runtime_error("zlib block " + std::to_string(b) + " does not decompress");
        out_at += want;
        at += size_t(cs);
    }
    if (out_at != p.bytes.size()) throw std::runtime_error("zlib blocks are shorter than declared");
    p.consumed = at;
    return p;
}

}  // namespace pathlet::trace::vti
