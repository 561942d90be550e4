// Internal entry points of the per-format pathline readers and writers (dispatch lives in
// pathline_io.cpp). Writers return the bytes; save_pathlines() writes them atomically.
// Tests use the option structs to produce every variant the readers accept.
#pragma once

#include "raw_polylines.hpp"

#include <string>
#include <string_view>

namespace pathlet::io {

RawPolylines read_vtk_legacy(std::string_view bytes, const std::string& file, LoadReport& report);
RawPolylines read_vtp(std::string_view bytes, const std::string& file, LoadReport& report);
Pathlines read_text_rows(std::string_view bytes, const std::string& file, const LoadOptions& opts, LoadReport& report);

struct VtkLegacyWriteOptions {
    bool binary = true;
    bool version51 = false;  // 5.1 OFFSETS/CONNECTIVITY layout; default 4.2 (read by every VTK)
};
std::string write_vtk_legacy(const Pathlines& lines, const VtkLegacyWriteOptions& opts);

struct VtpWriteOptions {
    enum class Encoding { Ascii, Inline, AppendedRaw, AppendedBase64 } encoding = Encoding::Inline;
    bool zlib = false;
    bool header64 = true;             // header_type UInt64 (else UInt32)
    bool big_endian = false;
    bool separate_header_chunk = false;  // base64: header encoded as its own padded chunk
    size_t block_size = 32768;           // zlib block size
    int pieces = 1;                      // split lines over this many <Piece>s
};
std::string write_vtp(const Pathlines& lines, const VtpWriteOptions& opts);

}  // namespace pathlet::io
