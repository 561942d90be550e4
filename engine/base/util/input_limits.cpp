#include "input_limits.hpp"

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
size_t max_json_bytes() { return size_t(env_number("PATHLET_MAX_JSON_BYTES", 64.0 * 1024 * 1024, 4096.0)); }
double max_coordinate() { return env_number("PATHLET_MAX_COORDINATE", 1e15, 1.0); }

JsonDepth json_nesting_depth(const std::string& text, int limit) {
    JsonDepth r;
    int depth = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '"') {  // skip a string, escapes included
            for (++i; i < text.size() && text[i] != '"'; ++i)
                if (text[i] == '\\') ++i;
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
            while (i < text.size() && text[i] != '\n') ++i;
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
            size_t e = text.find("*/", i + 2);
            i = e == std::string::npos ? text.size() : e + 1;
        } else if (c == '[' || c == '{') {
            if (++depth > r.depth) r.depth = depth;
            if (depth > limit && r.first_too_deep == size_t(-1)) r.first_too_deep = i;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return r;
}

}  // namespace pathlet::io
