#include "zlib_blocks.hpp"

#include "util/input_limits.hpp"

#include <zlib.h>

#include <bit>
#include <cstring>

namespace pathlet::io {

uint64_t ZlibBlockHeader::uncompressed_size() const {
    if (blocks == 0) return 0;
    uint64_t last = last_block_size ? last_block_size : block_size;
    return (blocks - 1) * block_size + last;
}

static void put_uint(std::string& out, uint64_t v, int bytes, bool big_endian) {
    for (int i = 0; i < bytes; ++i) {
        int shift = big_endian ? 8 * (bytes - 1 - i) : 8 * i;
        out += char((v >> shift) & 0xFF);
    }
}

std::string zlib_blocks_encode_header(const ZlibBlockHeader& h, int header_bytes, bool big_endian) {
    std::string out;
    put_uint(out, h.blocks, header_bytes, big_endian);
    put_uint(out, h.block_size, header_bytes, big_endian);
    put_uint(out, h.last_block_size, header_bytes, big_endian);
    for (auto c : h.compressed) put_uint(out, c, header_bytes, big_endian);
    return out;
}

std::string zlib_blocks_encode(std::string_view data, int header_bytes, bool big_endian, size_t block_size) {
    ZlibBlockHeader h;
    h.block_size = block_size;
    h.blocks = (data.size() + block_size - 1) / block_size;
    h.last_block_size = data.size() % block_size;
    std::string body;
    for (uint64_t b = 0; b < h.blocks; ++b) {
        size_t off = size_t(b * block_size);
        size_t n = std::min(block_size, data.size() - off);
        uLongf cap = compressBound(uLong(n));
        size_t at = body.size();
        body.resize(at + cap);
        compress2(reinterpret_cast<Bytef*>(body.data() + at), &cap, reinterpret_cast<const Bytef*>(data.data() + off),
                  uLong(n), Z_DEFAULT_COMPRESSION);
        body.resize(at + cap);
        h.compressed.push_back(cap);
    }
    return zlib_blocks_encode_header(h, header_bytes, big_endian) + body;
}

std::string zlib_blocks_implausible(const ZlibBlockHeader& h) {
    for (uint64_t i = 0; i < h.blocks && i < h.compressed.size(); ++i) {
        uint64_t want = (i + 1 == h.blocks && h.last_block_size) ? h.last_block_size : h.block_size;
        if (double(want) > double(h.compressed[i]) * max_inflate_ratio() + 64.0)
            return "zlib block " + std::to_string(i) + " claims " + std::to_string(want) + " bytes from " +
                   std::to_string(h.compressed[i]) + " compressed bytes, more than deflate can produce (ratio cap " +
                   std::to_string(int(max_inflate_ratio())) + ", PATHLET_MAX_INFLATE_RATIO)";
    }
    return "";
}

std::string zlib_blocks_decode(const ZlibBlockHeader& h, std::string_view blocks, char* out) {
    size_t in_at = 0, out_at = 0;
    for (uint64_t b = 0; b < h.blocks; ++b) {
        uint64_t want = (b + 1 == h.blocks && h.last_block_size) ? h.last_block_size : h.block_size;
        uint64_t csize = h.compressed[b];
        if (csize > blocks.size() - in_at)
            return "zlib block " + std::to_string(b) + " declares " + std::to_string(csize) + " compressed bytes but only " +
                   std::to_string(blocks.size() - in_at) + " remain (file truncated?)";
        uLongf got = uLongf(want);
        int rc = uncompress(reinterpret_cast<Bytef*>(out + out_at), &got,
                            reinterpret_cast<const Bytef*>(blocks.data() + in_at), uLong(csize));
        if (rc == Z_BUF_ERROR && got == want)
            return "zlib block " + std::to_string(b) + " inflates to more than its declared " + std::to_string(want) +
                   " bytes (corrupt header or decompression bomb)";
        if (rc != Z_OK)
            return "zlib block " + std::to_string(b) + " is corrupt (" + (rc == Z_DATA_ERROR ? "data error" : rc == Z_BUF_ERROR ? "truncated or oversized" : "zlib error " + std::to_string(rc)) + ")";
        if (got != want)
            return "zlib block " + std::to_string(b) + " inflates to " + std::to_string(got) + " bytes, header declares " +
                   std::to_string(want);
        in_at += size_t(csize);
        out_at += size_t(want);
    }
    return "";
}

}  // namespace pathlet::io
