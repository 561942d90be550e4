#include "polyline.hpp"

#include <algorithm>

namespace pathlet::trace {

float polyline_length(const std::vector<glm::vec3>& p) {
    float len = 0.0f;
    for (size_t i = 1; i < p.size(); ++i) len += glm::length(p[i] - p[i - 1]);
    return len;
}

void binomial_smooth(std::vector<glm::vec3>& p, int passes) {
    if (p.size() < 3) return;
    std::vector<glm::vec3> tmp(p.size());
    for (int pass = 0; pass < passes; ++pass) {
        tmp.front() = p.front();
        tmp.back() = p.back();
        for (size_t i = 1; i + 1 < p.size(); ++i) tmp[i] = 0.25f * (p[i - 1] + 2.0f * p[i] + p[i + 1]);
        p.swap(tmp);
    }
}

TracedLine resample_by_length(const TracedLine& in, float step) {
    TracedLine out;
    if (in.size() == 0) return out;
    auto emit = [&](size_t i, float f) {  // point f of the way from sample i to i+1
        const size_t j = std::min(i + 1, in.size() - 1);
        const float t = in.time[i] + (in.time[j] - in.time[i]) * f;
        // No second point at one float time (a long step of little time): loaders drop those.
        if (!out.time.empty() && !(t > out.time.back())) return;
        out.position.push_back(in.position[i] + (in.position[j] - in.position[i]) * f);
        out.time.push_back(t);
        out.velocity.push_back(in.velocity[i] + (in.velocity[j] - in.velocity[i]) * f);
    };
    emit(0, 0.0f);
    float next = step;  // arc length of the next output point
    float at = 0.0f;    // arc length at sample i
    for (size_t i = 0; i + 1 < in.size(); ++i) {
        const float seg = glm::length(in.position[i + 1] - in.position[i]);
        while (seg > 0.0f && next <= at + seg) {
            emit(i, (next - at) / seg);
            next += step;
        }
        at += seg;
    }
    // Keep the true end unless the last emitted point is (almost) on it.
    if (in.size() > 1 && at - (next - step) > 0.05f * step) emit(in.size() - 1, 0.0f);
    return out;
}

// Cell coordinates packed 21 bits each, +1 so that no real key is 0 (0 marks a free slot).
uint64_t ProximityHash::key(glm::ivec3 c) {
    return ((uint64_t(uint32_t(c.x) & 0x1fffff) << 42) | (uint64_t(uint32_t(c.y) & 0x1fffff) << 21) |
            uint64_t(uint32_t(c.z) & 0x1fffff)) + 1;
}

static size_t probe_start(uint64_t key, size_t mask) { return size_t((key * 0x9e3779b97f4a7c15ull) >> 20) & mask; }

uint32_t ProximityHash::find(uint64_t key) const {
    if (keys_.empty()) return UINT32_MAX;
    const size_t mask = keys_.size() - 1;
    for (size_t i = probe_start(key, mask);; i = (i + 1) & mask) {
        if (keys_[i] == key) return heads_[i];
        if (keys_[i] == 0) return UINT32_MAX;
    }
}

uint32_t* ProximityHash::slot(uint64_t key) {
    if (2 * (used_ + 1) > keys_.size()) grow();
    const size_t mask = keys_.size() - 1;
    for (size_t i = probe_start(key, mask);; i = (i + 1) & mask) {
        if (keys_[i] == key) return &heads_[i];
        if (keys_[i] == 0) {
            keys_[i] = key;
            heads_[i] = UINT32_MAX;
            ++used_;
            return &heads_[i];
        }
    }
}

void ProximityHash::grow() {
    std::vector<uint64_t> old_keys(std::max<size_t>(1024, keys_.size() * 2), 0);
    std::vector<uint32_t> old_heads(old_keys.size(), UINT32_MAX);
    old_keys.swap(keys_);
    old_heads.swap(heads_);
    const size_t mask = keys_.size() - 1;
    for (size_t j = 0; j < old_keys.size(); ++j) {
        if (old_keys[j] == 0) continue;
        size_t i = probe_start(old_keys[j], mask);
        while (keys_[i] != 0) i = (i + 1) & mask;
        keys_[i] = old_keys[j];
        heads_[i] = old_heads[j];
    }
}

void ProximityHash::insert(glm::vec3 p) {
    uint32_t* head = slot(key(cell(p)));
    next_.push_back(*head);
    *head = uint32_t(pts_.size());
    pts_.push_back(p);
}

void ProximityHash::merge(const ProximityHash& other) {
    for (const auto& p : other.pts_) insert(p);
}

void ProximityHash::clear() {
    std::fill(keys_.begin(), keys_.end(), 0);
    used_ = 0;
    pts_.clear();
    next_.clear();
}

bool ProximityHash::near(glm::vec3 p) const {
    if (r_ <= 0.0f) return false;
    const glm::ivec3 c = cell(p);
    const float r2 = r_ * r_;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                for (uint32_t i = find(key(c + glm::ivec3(dx, dy, dz))); i != UINT32_MAX; i = next_[i]) {
                    const glm::vec3 d = pts_[i] - p;
                    if (glm::dot(d, d) <= r2) return true;
                }
            }
    return false;
}

float ProximityHash::near_fraction(const std::vector<glm::vec3>& pts) const {
    if (pts.empty()) return 0.0f;
    size_t n = 0;
    for (const auto& p : pts) n += near(p) ? 1 : 0;
    return float(n) / float(pts.size());
}

}  // namespace pathlet::trace
