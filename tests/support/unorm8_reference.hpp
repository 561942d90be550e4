// The float -> 8-bit rule written out independently of engine/core/image_io.hpp's to_unorm8:
// clamp to [0,1], multiply by 255 in float (as the writers always did), round to nearest with
// halves away from zero (std::lround); NaN is 0. Tests compare to_unorm8 and the bytes that
// reach a file with it, never with to_unorm8 itself.
#pragma once

#include <algorithm>
#include <cmath>

namespace pathlet::test {

inline int reference_unorm8(float v) {
    if (std::isnan(v)) return 0;
    return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

}  // namespace pathlet::test
