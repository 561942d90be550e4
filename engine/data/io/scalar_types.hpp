// Element types of VTK arrays (legacy and XML names) and decoding of packed binary
// values in either byte order into float or int64 buffers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace pathlet::io {

enum class ScalarType { I8, U8, I16, U16, I32, U32, I64, U64, F32, F64 };

size_t scalar_size(ScalarType t);
bool is_float(ScalarType t);
const char* xml_name(ScalarType t);
std::optional<ScalarType> legacy_type(std::string_view name);  // "float", "vtktypeint64", ... (case-insensitive)
std::optional<ScalarType> xml_type(std::string_view name);     // "Float32", "Int64", ...

// Decodes `count` packed values at `src` (count * scalar_size bytes).
void decode_floats(const char* src, size_t count, ScalarType t, bool big_endian, float* out);
void decode_ints(const char* src, size_t count, ScalarType t, bool big_endian, int64_t* out);

// Heuristic for "declared big-endian but written little-endian" (or vice versa): true when
// many values are NaN/inf, astronomically large or denormal-tiny.
bool floats_look_garbled(const float* v, size_t n);

}  // namespace pathlet::io
