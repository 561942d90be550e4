#include <pathlet/line_chunks.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathlet {

void LineChunks::build(const Pathlines& pl) {
    chunks_.clear();
    line_begin_.assign(1, 0);
    segments_ = 0;
    constexpr float inf = std::numeric_limits<float>::infinity();
    for (const LineRange& r : pl.lines) {
        if (r.count >= 2) {
            for (uint32_t a = r.first; a + 1 < r.first + r.count; a += kSegments) {
                Chunk c;
                c.first = a;
                c.last = std::min(a + kSegments, r.first + r.count - 1);
                c.box = {glm::vec3(inf), glm::vec3(-inf)};
                for (uint32_t i = c.first; i <= c.last; ++i) {
                    const glm::vec3 p = pl.position[i];
                    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
                    c.box.lo = glm::min(c.box.lo, p);
                    c.box.hi = glm::max(c.box.hi, p);
                }
                chunks_.push_back(c);
                segments_ += c.last - c.first;
            }
        }
        line_begin_.push_back(uint32_t(chunks_.size()));
    }
}

}  // namespace pathlet
