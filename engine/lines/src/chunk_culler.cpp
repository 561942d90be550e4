#include "chunk_culler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathlet::lines {

namespace {
// Adds the time since construction to `ms` (the culler's own CPU work, no GL waits).
struct Timed {
    double& ms;
    std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
    ~Timed() { ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(); }
};
}  // namespace

// Consecutive pieces of one line join into one range: the level of detail widens every range
// to the kept points around it, which would draw the segments at a join twice.
void ChunkCuller::append(GpuScene::Ranges& r, const Piece& p) {
    if (!r.first.empty() && r.line.back() == p.line && r.first.back() + r.count.back() - 1 == p.first) {
        r.count.back() += p.count - 1;
    } else {
        r.first.push_back(p.first);
        r.count.push_back(p.count);
        r.line.push_back(p.line);
    }
    r.segments += size_t(p.count - 1);
}

void ChunkCuller::split(const GpuScene::Ranges& window, const LineChunks& chunks, const glm::vec3* points,
                        const glm::mat4& view_proj, float grow, bool occlusion) {
    view_proj_ = view_proj;
    if (visible_.size() != chunks.chunks().size()) visible_.assign(chunks.chunks().size(), 0);
    stats_ = {};
    Timed timed{stats_.cpu_ms};
    p1_.clear();
    rest_.clear();
    drawn2_.clear();
    phase1_ = {};
    phase2_ = {};
    for (size_t i = 0; i < window.first.size(); ++i) {
        const uint32_t line = window.line[i];
        const uint32_t f = uint32_t(window.first[i]), l = f + uint32_t(window.count[i]) - 1;
        for (uint32_t c = chunks.begin(line); c < chunks.end(line); ++c) {
            const LineChunks::Chunk& ch = chunks.chunks()[c];
            const uint32_t a = std::max(f, ch.first), b = std::min(l, ch.last);
            if (b <= a) continue;  // no segment of this chunk in the window
            ++stats_.chunks;
            // The piece's own box: the window may hold a few of the chunk's segments only.
            Bounds box = ch.box;
            if (a != ch.first || b != ch.last) {
                box = {glm::vec3(std::numeric_limits<float>::infinity()), glm::vec3(-std::numeric_limits<float>::infinity())};
                for (uint32_t i = a; i <= b; ++i)
                    if (std::isfinite(points[i].x) && std::isfinite(points[i].y) && std::isfinite(points[i].z))
                        box.lo = glm::min(box.lo, points[i]), box.hi = glm::max(box.hi, points[i]);
            }
            if (box.valid()) box.lo -= glm::vec3(grow), box.hi += glm::vec3(grow);
            // Outside the frustum when all eight corners of the grown box lie beyond one plane.
            bool outside = false;
            if (box.valid()) {
                int out[6] = {0, 0, 0, 0, 0, 0};
                for (int k = 0; k < 8; ++k) {
                    const glm::vec4 p = view_proj * glm::vec4(k & 1 ? box.hi.x : box.lo.x, k & 2 ? box.hi.y : box.lo.y,
                                                              k & 4 ? box.hi.z : box.lo.z, 1.0f);
                    out[0] += p.x < -p.w, out[1] += p.x > p.w, out[2] += p.y < -p.w;
                    out[3] += p.y > p.w, out[4] += p.z < -p.w, out[5] += p.z > p.w;
                }
                for (int plane : out) outside |= plane == 8;
            }
            if (outside) {
                ++stats_.frustum_culled;
                visible_[c] = 0;
                continue;
            }
            const Piece piece{c, GLint(a), GLsizei(b - a + 1), line, box};
            (visible_[c] || !occlusion ? p1_ : rest_).push_back(piece);
        }
    }
    for (const Piece& p : p1_) append(phase1_, p);
    stats_.phase1 = p1_.size();
}

// Hidden: every tile the grown box's screen rectangle touches holds only nearer depths than
// the box's nearest corner (window depth is monotonic in eye depth: a corner is the nearest).
bool ChunkCuller::hidden(const Bounds& box, TileDepth depth) const {
    if (!box.valid()) return false;
    const glm::vec3 lo = box.lo, hi = box.hi;
    glm::vec2 pmin(1e30f), pmax(-1e30f);
    float zmin = 1.0f;
    for (int k = 0; k < 8; ++k) {
        const glm::vec4 p = view_proj_ * glm::vec4(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z, 1.0f);
        if (!(p.w > 1e-6f)) return false;  // reaches behind the camera
        const glm::vec3 ndc = glm::vec3(p) / p.w;
        pmin = glm::min(pmin, glm::vec2(ndc));
        pmax = glm::max(pmax, glm::vec2(ndc));
        zmin = std::min(zmin, 0.5f * ndc.z + 0.5f);
    }
    if (zmin <= 0.0f) return false;
    const glm::ivec2 tiles = depth.tiles;
    const glm::vec2 size = glm::vec2(tiles * kTile);
    // Pixels the rectangle can touch (one extra on each side for rasterisation), then tiles.
    const glm::ivec2 a = glm::clamp(glm::ivec2(glm::floor((pmin * 0.5f + 0.5f) * size)) - 1, glm::ivec2(0), tiles * kTile - 1);
    const glm::ivec2 b = glm::clamp(glm::ivec2(glm::ceil((pmax * 0.5f + 0.5f) * size)) + 1, glm::ivec2(0), tiles * kTile - 1);
    for (int ty = a.y / kTile; ty <= b.y / kTile; ++ty)
        for (int tx = a.x / kTile; tx <= b.x / kTile; ++tx)
            if (depth.farthest[size_t(ty) * size_t(tiles.x) + size_t(tx)] >= zmin) return false;
    return true;
}

void ChunkCuller::test_rest(TileDepth depth) {
    Timed timed{stats_.cpu_ms};
    for (const Piece& p : rest_) {
        if (depth.farthest && hidden(p.box, depth)) {
            ++stats_.occluded;
            continue;
        }
        append(phase2_, p);
        drawn2_.push_back(p);
    }
    stats_.phase2 = drawn2_.size();
}

void ChunkCuller::remember(TileDepth depth) {
    Timed timed{stats_.cpu_ms};
    for (const Piece& p : rest_) visible_[p.chunk] = 0;
    for (const auto* list : {&p1_, &drawn2_})
        for (const Piece& p : *list) visible_[p.chunk] = depth.farthest && hidden(p.box, depth) ? 0 : 1;
}

}  // namespace pathlet::lines
