// vtkZLibDataCompressor block format: header [nBlocks, blockSize, lastBlockSize,
// compressedSize_0..n-1] (UInt32 or UInt64, file byte order) followed by the zlib blocks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pathlet::io {

struct ZlibBlockHeader {
    uint64_t blocks = 0, block_size = 0, last_block_size = 0;
    std::vector<uint64_t> compressed;
    // Total uncompressed size the header declares (lastBlockSize 0 = last block full).
    uint64_t uncompressed_size() const;
};

// Compresses `data` into header + blocks with the given header width (4 or 8) and byte order.
std::string zlib_blocks_encode(std::string_view data, int header_bytes, bool big_endian, size_t block_size = 32768);
std::string zlib_blocks_encode_header(const ZlibBlockHeader& h, int header_bytes, bool big_endian);

// "" when every block's claimed size is one deflate can produce from its compressed bytes
// (io::max_inflate_ratio()), else why not: checked before anything is allocated.
std::string zlib_blocks_implausible(const ZlibBlockHeader& h);

// Inflates block by block into `out` (which must already be sized to h.uncompressed_size());
// each block may produce at most its declared size, so a lying header cannot make it
// allocate or write more (no decompression bombs). Returns "" or what went wrong.
std::string zlib_blocks_decode(const ZlibBlockHeader& h, std::string_view blocks, char* out);

}  // namespace pathlet::io
