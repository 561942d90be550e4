// Decoding of VTK XML binary payloads for the .vti reader: base64, the UInt32/UInt64 size
// headers and vtkZLibDataCompressor blocks. Kept apart so the reader stays readable.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace pathlet::trace::vti {

// Decodes base64 in 4-character groups, so separately padded streams that were simply
// concatenated (as VTK writes header and data) decode in one go. Whitespace is skipped.
// Stops after `max_bytes` output bytes. Throws std::runtime_error on a bad character.
std::string base64_decode(std::string_view text, size_t max_bytes = SIZE_MAX);

struct Payload {
    std::string bytes;   // the decoded array bytes
    size_t consumed = 0; // bytes of the (decoded) input used, header included
};

// One array's binary block starting at `in`: [header][data], raw or zlib-compressed.
// header_size is 4 (UInt32) or 8 (UInt64). `limit` caps the decoded size (sanity check
// against the file size). Throws std::runtime_error with a short reason.
Payload decode_block(std::string_view in, size_t header_size, bool zlib, size_t limit);

}  // namespace pathlet::trace::vti
