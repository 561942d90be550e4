#include "limits.hpp"

#include <cstdlib>
#include <string>

namespace pathlet::io {
namespace {
double env_number(const char* name, double def, double min) {
    const char* v = std::getenv(name);
    if (!v || !*v) return def;
    char* end = nullptr;
    double d = std::strtod(v, &end);
    return (end && *end == '\0' && d >= min) ? d : def;
}
}  // namespace

double max_inflate_ratio() { return env_number("PATHLET_MAX_INFLATE_RATIO", 1032.0, 1.0); }
int max_json_depth() { return int(env_number("PATHLET_MAX_JSON_DEPTH", 128.0, 8.0)); }
double max_coordinate() { return env_number("PATHLET_MAX_COORDINATE", 1e15, 1.0); }

}  // namespace pathlet::io
