#include "native_cache.hpp"

#include "byte_reader.hpp"
#include "raw_polylines.hpp"
#include "units.hpp"

#include <algorithm>
#include <bit>
#include <cstring>

namespace pathlet::io {

static_assert(std::endian::native == std::endian::little, "the native cache is little-endian; add byte swapping");
static_assert(sizeof(glm::vec3) == 12 && sizeof(LineRange) == 8);

namespace {
size_t align16(size_t n) { return (n + 15) & ~size_t(15); }
template <class T> void put(std::string& s, size_t at, T v) { std::memcpy(s.data() + at, &v, sizeof v); }
template <class T> T get(std::string_view s, size_t at) { T v; std::memcpy(&v, s.data() + at, sizeof v); return v; }
}  // namespace

std::string encode_native(const Pathlines& pl) {
    const uint64_t n = pl.position.size(), l = pl.lines.size();
    size_t pos_off = kNativeHeaderSize;
    size_t time_off = align16(pos_off + n * 12);
    size_t vel_off = align16(time_off + n * 4);
    size_t line_off = align16(vel_off + n * 12);
    const std::string units = pl.units.length + '\0' + pl.units.time + '\0' + pl.units.velocity + '\0';
    const bool has_units = units.size() > 3;
    size_t units_off = has_units ? align16(line_off + l * 8) : 0;
    size_t total = has_units ? units_off + units.size() : line_off + l * 8;
    std::string s(total, '\0');
    std::memcpy(s.data(), kNativeMagic.data(), kNativeMagic.size());
    put<uint32_t>(s, 8, kNativeVersion);
    put<uint32_t>(s, 12, uint32_t(kNativeHeaderSize));
    put<uint64_t>(s, 16, n);
    put<uint64_t>(s, 24, l);
    put<uint64_t>(s, 32, pos_off);
    put<uint64_t>(s, 40, time_off);
    put<uint64_t>(s, 48, vel_off);
    put<uint64_t>(s, 56, line_off);
    put<uint64_t>(s, 64, total);
    put<uint64_t>(s, 72, units_off);
    put<uint64_t>(s, 80, has_units ? units.size() : 0);
    if (has_units) std::memcpy(s.data() + units_off, units.data(), units.size());
    if (n) {
        std::memcpy(s.data() + pos_off, pl.position.data(), n * 12);
        std::memcpy(s.data() + time_off, pl.time.data(), n * 4);
        std::memcpy(s.data() + vel_off, pl.velocity.data(), n * 12);
    }
    if (l) std::memcpy(s.data() + line_off, pl.lines.data(), l * 8);
    return s;
}

Pathlines decode_native(std::string_view b, const std::string& file, LoadReport& report) {
    if (b.size() < kNativeHeaderSize)
        fail_at(file, at_byte(b.size()), "native cache header is " + std::to_string(kNativeHeaderSize) +
                                             " bytes but the file has only " + std::to_string(b.size()) + " (truncated)");
    if (b.substr(0, 8) != kNativeMagic) fail_at(file, at_byte(0), "not a pathlet native cache (bad magic)");
    uint32_t version = get<uint32_t>(b, 8);
    if (version != kNativeVersion)
        fail_at(file, at_byte(8), "native cache version " + std::to_string(version) + " is not supported (this build reads " +
                                      std::to_string(kNativeVersion) + "); re-create the cache from the source data");
    report.format = "pathlet native cache v" + std::to_string(version);
    uint64_t n = get<uint64_t>(b, 16), l = get<uint64_t>(b, 24);
    uint64_t off[4] = {get<uint64_t>(b, 32), get<uint64_t>(b, 40), get<uint64_t>(b, 48), get<uint64_t>(b, 56)};
    uint64_t total = get<uint64_t>(b, 64);
    if (total != b.size())
        fail_at(file, at_byte(64), "header says the file is " + std::to_string(total) + " bytes but it is " +
                                       std::to_string(b.size()) + (total > b.size() ? " (truncated)" : " (trailing data)"));
    // Counts validated against the file size before anything is allocated.
    if (n > b.size() / 12 || l > b.size() / 8 || n > UINT32_MAX)
        fail_at(file, at_byte(16), "point/line counts (" + std::to_string(n) + ", " + std::to_string(l) +
                                       ") cannot fit in a " + std::to_string(b.size()) + "-byte file");
    const uint64_t sizes[4] = {n * 12, n * 4, n * 12, l * 8};
    const char* names[4] = {"positions", "times", "velocities", "lines"};
    for (int i = 0; i < 4; ++i)
        if (off[i] < kNativeHeaderSize || off[i] > b.size() || sizes[i] > b.size() - off[i])
            fail_at(file, at_byte(32 + 8 * i), std::string(names[i]) + " block at byte " + std::to_string(off[i]) +
                                                   " of " + std::to_string(sizes[i]) + " bytes lies outside the file");
    Pathlines pl;
    pl.position.resize(n);
    pl.time.resize(n);
    pl.velocity.resize(n);
    pl.lines.resize(l);
    if (n) {
        std::memcpy(pl.position.data(), b.data() + off[0], sizes[0]);
        std::memcpy(pl.time.data(), b.data() + off[1], sizes[1]);
        std::memcpy(pl.velocity.data(), b.data() + off[2], sizes[2]);
    }
    if (l) std::memcpy(pl.lines.data(), b.data() + off[3], sizes[3]);
    for (size_t i = 0; i < l; ++i)
        if (uint64_t(pl.lines[i].first) + pl.lines[i].count > n)
            fail_at(file, at_byte(off[3] + 8 * i), "line " + std::to_string(i) + " (points " + std::to_string(pl.lines[i].first) +
                                                       " + " + std::to_string(pl.lines[i].count) + ") runs past the " +
                                                       std::to_string(n) + " points");
    const uint64_t units_off = get<uint64_t>(b, 72), units_size = get<uint64_t>(b, 80);
    if (units_off != 0) {
        if (units_off < kNativeHeaderSize || units_off > b.size() || units_size > b.size() - units_off || units_size > 256)
            fail_at(file, at_byte(72), "units block at byte " + std::to_string(units_off) + " of " + std::to_string(units_size) +
                                           " bytes lies outside the file (or is longer than 256 bytes)");
        std::string_view block = b.substr(size_t(units_off), size_t(units_size));
        for (int i = 0; i < 3 && !block.empty(); ++i) {
            const size_t end = std::min(block.find('\0'), block.size());
            unit_slot(pl.units, i) = sanitize_unit(block.substr(0, end));
            block.remove_prefix(std::min(end + 1, block.size()));
        }
    }
    report.arrays = {"time (1 comp)", "velocity (3 comp)"};
    if (l == 0) report.warnings.push_back("the file holds no lines: empty pathline set");
    repair_pathlines(pl, report, file);
    return pl;
}

}  // namespace pathlet::io
