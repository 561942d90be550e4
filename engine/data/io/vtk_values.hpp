// Reading a counted run of numbers from a VTK file, ASCII tokens or packed binary, into
// floats or int64s, with the size checked against what is left of the file before any
// allocation. Shared by the legacy reader (big-endian binary) and the VTP ascii arrays.
#pragma once

#include "byte_reader.hpp"
#include "scalar_types.hpp"

#include <cmath>
#include <vector>

namespace pathlet::io {

// Fails unless `count` values of `type` can still fit in the cursor's data
// (binary: count*size bytes; ASCII: at least 2 characters per value).
void check_fits(Cursor& c, uint64_t count, ScalarType type, bool binary, const char* what);

template <class T>  // float or int64_t
std::vector<T> read_values(Cursor& c, uint64_t count, ScalarType type, bool binary, bool big_endian, const char* what) {
    check_fits(c, count, type, binary, what);
    std::vector<T> out(count);
    if (binary) {
        auto b = c.bytes(count * scalar_size(type), what);
        if constexpr (std::is_same_v<T, float>) decode_floats(b.data(), count, type, big_endian, out.data());
        else decode_ints(b.data(), count, type, big_endian, out.data());
        return out;
    }
    for (uint64_t i = 0; i < count; ++i) {
        auto t = c.token();
        if (t.empty())
            c.fail(std::string(what) + ": file ends after " + std::to_string(i) + " of " + std::to_string(count) +
                   " values (truncated, or the count is wrong)");
        if (!parse_number(t, out[i])) {
            double d;  // integers written as "3.0" by some tools
            if constexpr (std::is_same_v<T, int64_t>) {
                // Range first: casting nan, inf or 1e20 to int64 is undefined behaviour.
                if (parse_number(t, d) && d >= -9.0e15 && d <= 9.0e15 && d == std::trunc(d)) {
                    out[i] = int64_t(d);
                    continue;
                }
            }
            c.fail(std::string(what) + ": value " + std::to_string(i) + " is '" + std::string(t.substr(0, 40)) +
                   "', not a number (counts disagree with the data?)");
        }
    }
    return out;
}

}  // namespace pathlet::io
