// What a panel slider shows for a number (no ImGui here, so tests need no window): the value,
// or where it says "auto" (0 or below) the value in use, which a pass reports as a stat named
// like the parameter (gbuffer's line_width, the overlay's speed_min, speed_max and font_px).
#pragma once

#include <map>
#include <string>

namespace pathlet::view {

// Per pass ("pass.name") and under the bare name for the graph's variables.
using InUse = std::map<std::string, double>;

// The slider's format: "%d" or "%.4g", or "auto (1.109)" (ImGui shows a format without a
// conversion as it is) where `value` <= 0 and the pass uses another value.
std::string slider_format(const std::string& set_name, double value, bool is_int, const InUse& in_use);

}  // namespace pathlet::view
