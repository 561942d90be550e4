#include "scalar_types.hpp"

#include "byte_reader.hpp"

#include <bit>
#include <cmath>
#include <cstring>

namespace pathlet::io {

size_t scalar_size(ScalarType t) {
    switch (t) {
        case ScalarType::I8: case ScalarType::U8: return 1;
        case ScalarType::I16: case ScalarType::U16: return 2;
        case ScalarType::I32: case ScalarType::U32: case ScalarType::F32: return 4;
        default: return 8;
    }
}

bool is_float(ScalarType t) { return t == ScalarType::F32 || t == ScalarType::F64; }

const char* xml_name(ScalarType t) {
    static const char* names[] = {"Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32", "Int64", "UInt64", "Float32", "Float64"};
    return names[int(t)];
}

std::optional<ScalarType> legacy_type(std::string_view n) {
    struct { const char* name; ScalarType t; } table[] = {
        {"bit", ScalarType::U8},  // packed bits are rejected by callers; listed to give a clear message
        {"unsigned_char", ScalarType::U8}, {"char", ScalarType::I8}, {"signed_char", ScalarType::I8},
        {"unsigned_short", ScalarType::U16}, {"short", ScalarType::I16},
        {"unsigned_int", ScalarType::U32}, {"int", ScalarType::I32},
        {"unsigned_long", ScalarType::U64}, {"long", ScalarType::I64},
        {"vtktypeint8", ScalarType::I8}, {"vtktypeuint8", ScalarType::U8},
        {"vtktypeint16", ScalarType::I16}, {"vtktypeuint16", ScalarType::U16},
        {"vtktypeint32", ScalarType::I32}, {"vtktypeuint32", ScalarType::U32},
        {"vtktypeint64", ScalarType::I64}, {"vtktypeuint64", ScalarType::U64}, {"vtkidtype", ScalarType::I64},
        {"float", ScalarType::F32}, {"double", ScalarType::F64},
        {"vtktypefloat32", ScalarType::F32}, {"vtktypefloat64", ScalarType::F64},
    };
    for (auto& e : table)
        if (iequals(n, e.name)) return e.t;
    return std::nullopt;
}

std::optional<ScalarType> xml_type(std::string_view n) {
    for (int i = 0; i <= int(ScalarType::F64); ++i)
        if (n == xml_name(ScalarType(i))) return ScalarType(i);
    if (n == "Float") return ScalarType::F32;  // very old writers
    if (n == "Int") return ScalarType::I32;
    return std::nullopt;
}

namespace {
template <class T>
T load(const char* p, bool swap) {
    using U = std::conditional_t<sizeof(T) == 1, uint8_t,
              std::conditional_t<sizeof(T) == 2, uint16_t, std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>>>;
    U u;
    std::memcpy(&u, p, sizeof u);
    if (swap) {
        if constexpr (sizeof(U) == 2) u = __builtin_bswap16(u);
        if constexpr (sizeof(U) == 4) u = __builtin_bswap32(u);
        if constexpr (sizeof(U) == 8) u = __builtin_bswap64(u);
    }
    T v;
    std::memcpy(&v, &u, sizeof v);
    return v;
}

template <class Out, class F>
void dispatch(const char* src, size_t n, ScalarType t, bool big_endian, Out* out, F convert) {
    const bool swap = big_endian != (std::endian::native == std::endian::big);
    auto run = [&](auto tag) {
        using T = decltype(tag);
        if (!swap) {
            if constexpr (std::is_same_v<T, Out>) { if (n) std::memcpy(out, src, n * sizeof(T)); return; }
        }
        for (size_t i = 0; i < n; ++i) out[i] = convert(load<T>(src + i * sizeof(T), swap));
    };
    switch (t) {
        case ScalarType::I8: run(int8_t{}); break;
        case ScalarType::U8: run(uint8_t{}); break;
        case ScalarType::I16: run(int16_t{}); break;
        case ScalarType::U16: run(uint16_t{}); break;
        case ScalarType::I32: run(int32_t{}); break;
        case ScalarType::U32: run(uint32_t{}); break;
        case ScalarType::I64: run(int64_t{}); break;
        case ScalarType::U64: run(uint64_t{}); break;
        case ScalarType::F32: run(float{}); break;
        case ScalarType::F64: run(double{}); break;
    }
}
}  // namespace

void decode_floats(const char* src, size_t n, ScalarType t, bool big_endian, float* out) {
    dispatch(src, n, t, big_endian, out, [](auto v) { return float(v); });
}

void decode_ints(const char* src, size_t n, ScalarType t, bool big_endian, int64_t* out) {
    dispatch(src, n, t, big_endian, out, [](auto v) -> int64_t {
        using T = decltype(v);
        if constexpr (std::is_floating_point_v<T>) {
            return std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 9e18 ? int64_t(v) : int64_t(-1);
        } else if constexpr (std::is_same_v<T, uint64_t>) {
            return v > uint64_t(INT64_MAX) ? int64_t(-1) : int64_t(v);  // -1 fails range checks later
        } else {
            return int64_t(v);
        }
    });
}

bool floats_look_garbled(const float* v, size_t n) {
    if (n == 0) return false;
    size_t bad = 0;
    for (size_t i = 0; i < n; ++i) {
        float a = std::fabs(v[i]);
        if (!std::isfinite(a) || a > 1e15f || (a != 0.0f && a < 1e-30f)) ++bad;
    }
    return bad * 4 > n;  // more than a quarter
}

}  // namespace pathlet::io
