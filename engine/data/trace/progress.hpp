// Progress reporting shared by the tracer, marching cubes and the phantom: a callback
// with the fraction done (0..1) and what is being done. May be empty.
#pragma once

#include <functional>
#include <string_view>

namespace pathlet::trace {

using Progress = std::function<void(double fraction, std::string_view stage)>;

inline void report(const Progress& p, double fraction, std::string_view stage) {
    if (p) p(fraction, stage);
}

}  // namespace pathlet::trace
