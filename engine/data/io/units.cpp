#include "units.hpp"

#include <cctype>
#include <stdexcept>

namespace pathlet::io {

namespace {
bool iequal(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (std::tolower((unsigned char)a[i]) != std::tolower((unsigned char)b[i])) return false;
    return true;
}
}  // namespace

int unit_array_index(std::string_view name) {
    const char* snake[3] = {"length_unit", "time_unit", "velocity_unit"};
    for (int i = 0; i < 3; ++i)
        if (iequal(name, kUnitArrays[i]) || iequal(name, snake[i])) return i;
    return -1;
}

std::string& unit_slot(Units& u, int index) { return index == 0 ? u.length : index == 1 ? u.time : u.velocity; }

std::string sanitize_unit(std::string_view raw) {
    while (!raw.empty() && (raw.back() == ' ' || raw.back() == '\0')) raw.remove_suffix(1);
    while (!raw.empty() && raw.front() == ' ') raw.remove_prefix(1);
    if (raw.empty() || raw.size() > 24) return "";
    for (char c : raw)
        if ((unsigned char)c < 0x20 || (unsigned char)c >= 0x7f) return "";
    return std::string(raw);
}

std::string derived_velocity_unit(const Units& u) {
    return u.length.empty() || u.time.empty() ? "" : u.length + "/" + u.time;
}

void apply_units_option(Units& u, const std::string& spec) {
    if (spec.empty()) return;
    const size_t comma = spec.find(',');
    const std::string length = spec.substr(0, comma);
    const std::string velocity = comma == std::string::npos ? "" : spec.substr(comma + 1);
    auto check = [&](const std::string& s, const char* what) {
        if (!s.empty() && sanitize_unit(s) != s)
            throw std::invalid_argument(std::string("--units: the ") + what + " unit '" + s +
                                        "' must be 1-24 printable characters without commas or spaces at the ends");
    };
    check(length, "length");
    check(velocity, "velocity");
    if (length.empty() && velocity.empty())
        throw std::invalid_argument("--units expects LENGTH[,VELOCITY], e.g. mm or m,m/s; got '" + spec + "'");
    if (velocity.find(',') != std::string::npos)
        throw std::invalid_argument("--units expects at most two units, LENGTH,VELOCITY; got '" + spec + "'");
    if (!length.empty()) u.length = length;
    if (!velocity.empty()) u.velocity = velocity;
    else if (u.velocity.empty()) u.velocity = derived_velocity_unit(u);
    // A velocity per time unit names the time's unit where the file did not (the time label's
    // "s" for VTK data loaded with --units mm,m/s).
    const size_t slash = u.velocity.rfind('/');
    if (u.time.empty() && slash != std::string::npos && slash + 1 < u.velocity.size()) {
        const std::string t = u.velocity.substr(slash + 1);
        for (const char* known : {"s", "ms", "min", "h"})
            if (t == known) u.time = t;
    }
}

std::string describe_units(const Units& u) {
    std::string s;
    auto add = [&](const char* what, const std::string& v) {
        if (!v.empty()) s += (s.empty() ? "" : ", ") + std::string(what) + " " + v;
    };
    add("length", u.length);
    add("time", u.time);
    add("velocity", u.velocity);
    return s.empty() ? "not given" : s;
}

}  // namespace pathlet::io
