#include "tracer.hpp"

#include "flow_sampler.hpp"
#include "hash_random.hpp"
#include "polyline.hpp"
#include "rk4.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

namespace pathlet::trace {
namespace {

// One direction from (p, t): appends samples after the start; returns the time used.
float integrate_direction(const FlowSampler& flow, glm::vec3 p, float t, float dir, float budget,
                          const TraceOptions& o, float min_speed, TracedLine& out, uint64_t& steps) {
    const float h = o.step * flow.grid().min_spacing();
    auto vel = [&](glm::vec3 q, float tq) { return flow.velocity(q, tq); };
    float used = 0.0f;
    glm::vec3 v = vel(p, t);
    for (int n = 0; n < o.max_steps; ++n) {
        const float speed = glm::length(v);
        if (!(speed >= min_speed) || speed == 0.0f) break;
        const float window = dir > 0 ? o.time_end - t : t - o.time_begin;
        const float dt = std::min({h / speed, o.max_dt, budget - used, window});
        // A step below float resolution at this time (1e-7 s at 18 s) gives no new time: a point
        // with the last one's time, which every loader drops (a generated and a cached phantom
        // would then differ by those points).
        if (dt <= 1e-7f || t + dir * dt == t) break;
        const glm::vec3 q = rk4_step(vel, p, t, dir * dt, v);
        ++steps;
        if (!flow.inside(q)) break;
        p = q;
        t += dir * dt;
        used += dt;
        v = vel(p, t);
        out.position.push_back(p);
        out.time.push_back(t);
        out.velocity.push_back(v);
    }
    return used;
}

void reverse_line(TracedLine& l) {
    std::reverse(l.position.begin(), l.position.end());
    std::reverse(l.time.begin(), l.time.end());
    std::reverse(l.velocity.begin(), l.velocity.end());
}

// Calls fn(i) for i in [0, n) on up to `threads` threads; results go to fixed slots.
template <class Fn>
void parallel_for(size_t n, int threads, const Fn& fn) {
    const size_t workers = std::min<size_t>(n, size_t(std::max(1, threads)));
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i; (i = next.fetch_add(1)) < n;) fn(i);
    };
    std::vector<std::thread> pool;
    for (size_t w = 1; w < workers; ++w) pool.emplace_back(work);
    work();
    for (auto& th : pool) th.join();
}

struct Candidate {
    size_t voxel = 0;
    TracedLine line;
    float length = 0.0f;
    uint64_t steps = 0;
    std::vector<uint8_t> near_before{};  // per point: near a line accepted before this batch
};

void append_line(Pathlines& out, const TracedLine& l) {
    out.lines.push_back({uint32_t(out.position.size()), uint32_t(l.size())});
    out.position.insert(out.position.end(), l.position.begin(), l.position.end());
    out.time.insert(out.time.end(), l.time.begin(), l.time.end());
    out.velocity.insert(out.velocity.end(), l.velocity.begin(), l.velocity.end());
}

}  // namespace

// A line from `voxel`, its seed jittered inside the voxel and its release time drawn from the
// hash `h`: traced, smoothed and resampled into c.line (c.length, c.steps).
static void trace_seed(const FlowSampler& flow, size_t voxel, uint64_t h, const TraceOptions& o, float min_speed,
                       float resample, Candidate& c) {
    const Grid& g = flow.grid();
    const glm::vec3 jitter(unit_float(hash64(h, 1)) - 0.5f, unit_float(hash64(h, 2)) - 0.5f,
                           unit_float(hash64(h, 3)) - 0.5f);
    glm::vec3 seed = g.point(g.coord(voxel)) + jitter * o.seed_jitter * g.spacing;
    if (!flow.inside(seed)) seed = g.point(g.coord(voxel));
    const float t0 = o.time_begin + unit_float(hash64(h, 4)) * (o.time_end - o.time_begin);
    TracedLine raw = integrate_line(flow, seed, t0, o, min_speed, &c.steps);
    binomial_smooth(raw.position, o.smooth_passes);
    c.line = resample_by_length(raw, resample);
    c.length = polyline_length(c.line.position);
}

// TraceOptions::density: density - 1 companions per accepted line, in blocks after the accepted
// lines. A companion is the first of a few seeds in its line's voxel that gives a line of
// min_length; when none does (a voxel near the outlet), a copy of the accepted line, so the
// count is exact. Deterministic: each companion's seeds hash from its voxel, block and attempt.
static void add_companions(const FlowSampler& flow, const std::vector<size_t>& accepted, const TraceOptions& o,
                           float min_speed, float resample, int threads, Pathlines& out, TraceStats& st) {
    constexpr int kAttempts = 8;
    const size_t n = accepted.size();
    const size_t blocks = size_t(o.density - 1);
    std::vector<Candidate> comp(n * blocks);
    std::atomic<uint64_t> steps{0};
    parallel_for(comp.size(), threads, [&](size_t i) {
        const size_t line = i % n, block = 1 + i / n;
        Candidate& c = comp[i];
        for (int a = 0; a < kAttempts; ++a) {
            const uint64_t h = hash64(hash64(accepted[line], o.seed ^ 0xc0b1ull), block * kAttempts + size_t(a));
            trace_seed(flow, accepted[line], h, o, min_speed, resample, c);
            if (c.line.size() >= 2 && c.length >= o.min_length) break;
            c.line = {};
        }
        steps += c.steps;
    });
    st.particle_steps += steps;
    for (size_t i = 0; i < comp.size(); ++i) {
        if (comp[i].line.size() < 2) {  // the accepted line again (copied first: `out` grows)
            const LineRange r = out.lines[i % n];
            TracedLine& copy = comp[i].line;
            copy.position.assign(out.position.begin() + r.first, out.position.begin() + r.first + r.count);
            copy.time.assign(out.time.begin() + r.first, out.time.begin() + r.first + r.count);
            copy.velocity.assign(out.velocity.begin() + r.first, out.velocity.begin() + r.first + r.count);
        }
        append_line(out, comp[i].line);
        comp[i].line = {};
    }
}

TracedLine integrate_line(const FlowSampler& flow, glm::vec3 seed, float t0, const TraceOptions& o, float min_speed,
                          uint64_t* steps) {
    uint64_t n = 0;
    TracedLine back, line;
    float used = 0.0f;
    if (o.bidirectional) {
        used = integrate_direction(flow, seed, t0, -1.0f, 0.5f * o.max_line_time, o, min_speed, back, n);
        reverse_line(back);
    }
    line = std::move(back);
    line.position.push_back(seed);
    line.time.push_back(t0);
    line.velocity.push_back(flow.velocity(seed, t0));
    integrate_direction(flow, seed, t0, 1.0f, o.max_line_time - used, o, min_speed, line, n);
    if (steps) *steps += n;
    return line;
}

namespace {

void check_trace_inputs(const VelocityField& field, const TraceOptions& o) {
    const Grid& g = field.grid;
    if (field.frames.empty() || g.count() == 0 || field.frames[0].size() != g.count())
        throw DataError(field.source + ": velocity field is empty or inconsistent");
    if (!(o.step > 0.0f) || !(o.time_end > o.time_begin) || !(o.max_line_time > 0.0f))
        throw DataError(field.source + ": trace options need step > 0, time_end > time_begin, max_line_time > 0");
}

// Seed order: vessel voxels sorted by a hash, so consecutive seeds are spread out.
std::vector<std::pair<uint64_t, uint32_t>> seed_order(const VelocityField& field, uint64_t seed) {
    std::vector<std::pair<uint64_t, uint32_t>> keyed;
    for (size_t i = 0; i < field.grid.count(); ++i)
        if (field.inside_voxel(i)) keyed.emplace_back(hash64(i, seed), uint32_t(i));
    std::sort(keyed.begin(), keyed.end());
    return keyed;
}

// Calls fn at a polyline's points and between them every `sub` or less: marks the voxels it
// crosses (sub-steps of half a voxel), feeds the proximity hash.
template <class Fn>
void walk_polyline(const std::vector<glm::vec3>& pts, float sub, const Fn& fn) {
    if (pts.empty()) return;
    fn(pts[0]);
    for (size_t i = 1; i < pts.size(); ++i) {
        const int n = std::max(1, int(std::ceil(glm::length(pts[i] - pts[i - 1]) / sub)));
        for (int k = 1; k <= n; ++k) fn(pts[i - 1] + (pts[i] - pts[i - 1]) * (float(k) / float(n)));
    }
}

}  // namespace

Pathlines trace_pathlines(const VelocityField& field, const TraceOptions& o, const Progress& progress, TraceStats* stats_out) {
    check_trace_inputs(field, o);
    const Grid& g = field.grid;

    const FlowSampler flow(field, o.periodic, o.pulsatile);
    const float min_speed = o.min_speed_fraction * field.max_speed() * (o.pulsatile ? o.pulsatile->peak : 1.0f);
    const float resample = o.resample_step > 0.0f ? o.resample_step : g.min_spacing();
    const int threads = o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    const size_t batch = size_t(std::max(1, o.batch));

    const std::vector<std::pair<uint64_t, uint32_t>> keyed = seed_order(field, o.seed);

    TraceStats st;
    st.vessel_voxels = keyed.size();
    // kNear: crossed by a line rejected as too close to accepted ones, so it is within
    // min_distance of a line; not seeded again, but not counted as covered either.
    enum : uint8_t { kFree = 0, kTried = 1, kNear = 2, kCovered = 3 };
    std::vector<uint8_t> state(g.count(), kFree);
    auto cover = [&](glm::vec3 p) {
        const glm::ivec3 c = g.nearest(p);
        if (!g.in_range(c)) return;
        uint8_t& s = state[g.index(c)];
        if (s != kCovered && field.inside_voxel(g.index(c))) ++st.covered_voxels;
        s = kCovered;
    };
    auto mark_near = [&](glm::vec3 p) {
        const glm::ivec3 c = g.nearest(p);
        if (g.in_range(c) && state[g.index(c)] == kFree) state[g.index(c)] = kNear;
    };
    // Accepted points: `near` up to the last batch (queried in parallel), `near_batch` this
    // batch (queried in order while accepting) - together the same answer as one hash.
    ProximityHash near(o.min_distance), near_batch(o.min_distance);
    auto close_fraction = [&](const Candidate& c) {
        size_t n = 0;
        for (size_t k = 0; k < c.line.size(); ++k) n += (c.near_before[k] || near_batch.near(c.line.position[k])) ? 1 : 0;
        return float(n) / float(std::max<size_t>(1, c.line.size()));
    };

    Pathlines out;
    std::vector<size_t> accepted;  // the seed voxel of each accepted line
    size_t cursor = 0;
    std::vector<Candidate> cands;
    while (cursor < keyed.size() && (o.max_lines == 0 || out.lines.size() < o.max_lines)) {
        cands.clear();
        near_batch.clear();
        for (; cursor < keyed.size() && cands.size() < batch; ++cursor) {
            const uint32_t v = keyed[cursor].second;
            if (state[v] != kFree) continue;
            state[v] = kTried;
            cands.push_back({v, {}, 0.0f, 0});
        }
        parallel_for(cands.size(), threads, [&](size_t i) {
            Candidate& c = cands[i];
            trace_seed(flow, c.voxel, hash64(c.voxel, o.seed ^ 0x5eedull), o, min_speed, resample, c);
            // The global proximity hash is read-only during the parallel phase.
            if (o.min_distance > 0.0f) {
                c.near_before.resize(c.line.size());
                for (size_t k = 0; k < c.line.size(); ++k) c.near_before[k] = near.near(c.line.position[k]);
            }
        });

        // Accept or reject in seed order: the only place state changes.
        for (Candidate& c : cands) {
            ++st.candidates;
            st.particle_steps += c.steps;
            if (state[c.voxel] == kCovered) { ++st.skipped_covered; continue; }
            if (c.line.size() < 2 || c.length < o.min_length) { ++st.rejected_short; continue; }
            if (o.min_distance > 0.0f && close_fraction(c) >= o.close_fraction) {
                // Its voxels are within min_distance of accepted lines: no need to seed there again.
                ++st.rejected_close;
                walk_polyline(c.line.position, 0.5f * g.min_spacing(), mark_near);
                continue;
            }
            if (o.max_lines && out.lines.size() >= o.max_lines) break;
            append_line(out, c.line);
            accepted.push_back(c.voxel);
            walk_polyline(c.line.position, 0.5f * g.min_spacing(), cover);
            cover(g.point(g.coord(c.voxel)));
            if (o.min_distance > 0.0f) walk_polyline(c.line.position, 0.5f * o.min_distance, [&](glm::vec3 p) { near_batch.insert(p); });
        }
        near.merge(near_batch);
        report(progress, keyed.empty() ? 1.0 : double(cursor) / double(keyed.size()), "tracing");
    }
    if (o.density > 1) add_companions(flow, accepted, o, min_speed, resample, threads, out, st);
    report(progress, 1.0, "tracing");
    if (stats_out) *stats_out = st;
    out.units = {field.units.length, "s", field.units.velocity};
    return out;
}

}  // namespace pathlet::trace
