// --shard I/N (render and bench): part I (0-based, as Slurm's $SLURM_ARRAY_TASK_ID with
// --array=0-(N-1)) of N. Item k belongs to shard k % N: deterministic, balanced, and the
// union of all shards is exactly the unsharded work.
#pragma once

#include <stdexcept>
#include <string>

namespace pathlet::cli {

struct Shard {
    int index = 0, count = 1;
    bool owns(size_t item) const { return int(item % size_t(count)) == index; }
    bool active() const { return count > 1; }
};

// Throws std::invalid_argument with the expected form.
inline Shard parse_shard(const std::string& text) {
    const std::string hint = "--shard: expected I/N with 0 <= I < N (e.g. 0/3), got '" + text + "'";
    size_t slash = text.find('/');
    if (slash == std::string::npos || slash == 0 || slash + 1 >= text.size()) throw std::invalid_argument(hint);
    for (size_t i = 0; i < text.size(); ++i)
        if (i != slash && !std::isdigit(static_cast<unsigned char>(text[i]))) throw std::invalid_argument(hint);
    Shard s;
    try {
        s.index = std::stoi(text.substr(0, slash));
        s.count = std::stoi(text.substr(slash + 1));
    } catch (const std::exception&) {
        throw std::invalid_argument(hint);
    }
    if (s.count < 1 || s.index < 0 || s.index >= s.count) throw std::invalid_argument(hint);
    return s;
}

}  // namespace pathlet::cli
