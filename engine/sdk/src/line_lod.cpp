#include <pathlet/line_lod.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathlet {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Distance from p to the box (0 inside).
float distance_to_box(glm::vec3 p, const Bounds& b) {
    glm::vec3 d = glm::max(glm::max(b.lo - p, p - b.hi), glm::vec3(0.0f));
    return glm::length(d);
}

}  // namespace

void LineLod::build(const Pathlines& pl, float speed_range) {
    const size_t n = pl.position.size();
    keep_.assign(n, kInf);
    line_box_.assign(pl.lines.size(), Bounds{});
    line_first_.resize(pl.lines.size());
    for (size_t li = 0; li < pl.lines.size(); ++li) line_first_[li] = pl.lines[li].first;
    const float inv_range = speed_range > 0.0f ? 1.0f / speed_range : 0.0f;
    std::vector<float> speed(n, 0.0f);
    for (size_t i = 0; i < n && i < pl.velocity.size(); ++i) speed[i] = glm::length(pl.velocity[i]);
    const bool timed = pl.time.size() >= n;

    struct Span {
        uint32_t a, b;
        float cap;  // the parent's tolerance: a child is never kept without its parent
    };
    std::vector<Span> stack;
    for (size_t li = 0; li < pl.lines.size(); ++li) {
        const LineRange r = pl.lines[li];
        Bounds box{glm::vec3(kInf), glm::vec3(-kInf)};
        for (uint32_t k = 0; k < r.count; ++k)
            if (finite(pl.position[r.first + k])) {
                box.lo = glm::min(box.lo, pl.position[r.first + k]);
                box.hi = glm::max(box.hi, pl.position[r.first + k]);
            }
        line_box_[li] = box;
        if (r.count < 3) continue;
        stack.push_back({r.first, r.first + r.count - 1, kInf});
        while (!stack.empty()) {
            const Span s = stack.back();
            stack.pop_back();
            if (s.b - s.a < 2) continue;
            const glm::vec3 pa = pl.position[s.a], pb = pl.position[s.b];
            const float ta = timed ? pl.time[s.a] : 0.0f, tb = timed ? pl.time[s.b] : 0.0f;
            const bool bad_chord = !finite(pa) || !finite(pb);
            // The split point is the worst one; the chord's error is the worst over the span.
            const int64_t mid = s.a + (s.b - s.a) / 2;
            uint32_t worst = uint32_t(mid);
            float worst_err = -1.0f;
            for (uint32_t j = s.a + 1; j < s.b; ++j) {
                const float dt = tb - ta;
                const float u = timed && dt > 1e-12f ? (pl.time[j] - ta) / dt : float(j - s.a) / float(s.b - s.a);
                float err;
                if (bad_chord || !finite(pl.position[j]) || !std::isfinite(u)) {
                    err = kInf;  // never simplify across bad points: the kit skips them exactly
                } else {
                    err = glm::length(pl.position[j] - (pa + u * (pb - pa)));
                    const float ds = std::fabs(speed[j] - (speed[s.a] + u * (speed[s.b] - speed[s.a]))) * inv_range;
                    if (ds > kSpeedTolerance) err = kInf;
                }
                // Ties go to the point nearest the middle: a straight run splits in halves,
                // not one point at a time (which would be quadratic).
                if (err > worst_err || (err == worst_err && std::abs(int64_t(j) - mid) < std::abs(int64_t(worst) - mid))) {
                    worst_err = err;
                    worst = j;
                }
            }
            const float tol = std::min(worst_err, s.cap);
            keep_[worst] = tol;
            stack.push_back({s.a, worst, tol});
            stack.push_back({worst, s.b, tol});
        }
    }
}

float LineLod::tolerance(uint32_t line, glm::vec3 eye, float scale, bool perspective, float lod_px) const {
    const float d = perspective ? distance_to_box(eye, line_box_[line]) : 1.0f;
    // A line without a finite point has no box (d = inf); a bad camera gives NaN. Keep eps
    // finite and >= 0 so the line's ends (tolerance +inf) always stop the scans of select().
    float eps = lod_px * scale * d;
    if (!(eps >= 0.0f)) eps = 0.0f;
    return std::min(eps, std::numeric_limits<float>::max());
}

void LineLod::select(const std::vector<GLint>& first, const std::vector<GLsizei>& count,
                     const std::vector<uint32_t>& line, glm::vec3 eye, float scale, bool perspective, float lod_px,
                     Strips& out, uint32_t max_skip) const {
    max_skip = std::max<uint32_t>(max_skip, 1);
    out.index.clear();
    out.count.clear();
    out.offset.clear();
    out.segments = 0;
    for (size_t i = 0; i < first.size(); ++i) {
        // Points at 0 tolerance (exactly on the chord) may go even at eps = 0 (camera inside
        // the box): they add nothing to the picture.
        const float eps = tolerance(line[i], eye, scale, perspective, lod_px);
        const uint32_t f = uint32_t(first[i]), l = uint32_t(first[i] + count[i] - 1);
        // The line's first point: every max_skip-th point from it is kept (line_cull_chunks.comp
        // has the same rule).
        const uint32_t line_first = line_first_[line[i]];
        auto kept = [&](uint32_t j) { return keep_[j] > eps || (j - line_first) % max_skip == 0; };
        // The kept points around [f, l]; line ends are always kept (tolerance +inf).
        uint32_t a = f, b = l;
        while (!kept(a)) --a;
        while (!kept(b)) ++b;
        const size_t start = out.index.size();
        out.index.push_back(a);
        for (uint32_t j = a + 1; j < b; ++j)
            if (kept(j)) out.index.push_back(j);
        out.index.push_back(b);
        const size_t n = out.index.size() - start;
        out.count.push_back(GLsizei(n));
        out.offset.push_back(reinterpret_cast<const void*>(start * sizeof(GLuint)));
        out.segments += n - 1;
    }
}

}  // namespace pathlet
