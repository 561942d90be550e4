// The native binary cache (.pathlet): a fixed little-endian header, then the arrays at
// 16-byte-aligned offsets, so loading is one read plus copies (or an mmap).
//
//   0  char[8]  magic "PATHLET\0"
//   8  u32      version (1)
//  12  u32      header size in bytes (96)
//  16  u64      point count N
//  24  u64      line count L
//  32  u64      offset of positions  (N * 3 float32)
//  40  u64      offset of times      (N float32)
//  48  u64      offset of velocities (N * 3 float32)
//  56  u64      offset of lines      (L * {u32 first, u32 count})
//  64  u64      total file size
//  72  u64      offset of the units block, 0 = none (files from before units: zero)
//  80  u64      size of the units block: "length\0time\0velocity\0", at most 256 bytes
//  88  u8[8]    reserved, zero
#pragma once

#include "pathline_io.hpp"

#include <string>
#include <string_view>

namespace pathlet::io {

inline constexpr std::string_view kNativeMagic{"PATHLET\0", 8};
inline constexpr uint32_t kNativeVersion = 1;
inline constexpr size_t kNativeHeaderSize = 96;

std::string encode_native(const Pathlines& lines);
Pathlines decode_native(std::string_view bytes, const std::string& file, LoadReport& report);

}  // namespace pathlet::io
