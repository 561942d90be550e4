#include "view/panel_values.hpp"

#include <cstdio>

namespace pathlet::view {

std::string slider_format(const std::string& set_name, double value, bool is_int, const InUse& in_use) {
    const auto it = in_use.find(set_name);
    if (value > 0.0 || it == in_use.end() || it->second == value) return is_int ? "%d" : "%.4g";
    char buf[64];
    std::snprintf(buf, sizeof buf, "auto (%.4g)", it->second);
    return buf;
}

}  // namespace pathlet::view
