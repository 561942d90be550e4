// Tracer on analytic fields: exact straight lines, RK4 circles, time interpolation,
// coverage, filtering, smoothing and thread-count independence.
#include "field_fixtures.hpp"

#include "trace/flow_sampler.hpp"
#include "trace/polyline.hpp"
#include "trace/tracer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace pathlet;
using namespace pathlet::trace;

namespace {

TraceOptions one_way(float max_time) {
    TraceOptions o;
    o.bidirectional = false;
    o.max_line_time = max_time;
    o.time_begin = 0.0f;
    o.time_end = 100.0f;
    o.max_dt = 1.0f;
    return o;
}

// Voxels whose cube is touched by the lines, walked in quarter-voxel steps.
std::set<size_t> crossed_voxels(const Grid& g, const Pathlines& pl) {
    std::set<size_t> out;
    for (const auto& l : pl.lines)
        for (uint32_t i = l.first; i < l.first + l.count; ++i) {
            const glm::vec3 a = pl.position[i], b = pl.position[std::min(i + 1, l.first + l.count - 1)];
            const int n = std::max(1, int(std::ceil(glm::length(b - a) / 0.25f)));
            for (int k = 0; k <= n; ++k) {
                const glm::ivec3 c = g.nearest(a + (b - a) * (float(k) / float(n)));
                if (g.in_range(c)) out.insert(g.index(c));
            }
        }
    return out;
}

VelocityField sphere_channel() {
    auto f = test::make_field({24, 24, 24}, [](glm::vec3) { return glm::vec3(5.0f, 0.0f, 0.0f); });
    test::mask_sphere(f, glm::vec3(11.5f), 9.0f);
    return f;
}

}  // namespace

TEST(Tracer, UniformFlowGivesStraightLineOfExactLengthAndTime) {
    const auto f = test::make_field({21, 11, 11}, [](glm::vec3) { return glm::vec3(10.0f, 0.0f, 0.0f); });
    const FlowSampler flow(f, false, std::nullopt);
    const TracedLine l = integrate_line(flow, {2.0f, 5.0f, 5.0f}, 0.0f, one_way(1.0f), 1e-3f);
    ASSERT_GE(l.size(), 10u);
    EXPECT_NEAR(l.position.back().x, 12.0f, 1e-4f);
    EXPECT_NEAR(l.time.back(), 1.0f, 1e-5f);
    EXPECT_NEAR(polyline_length(l.position), 10.0f, 1e-4f);
    for (size_t i = 0; i < l.size(); ++i) {
        EXPECT_FLOAT_EQ(l.position[i].y, 5.0f);
        EXPECT_FLOAT_EQ(l.position[i].z, 5.0f);
        EXPECT_NEAR(l.position[i].x - 2.0f, 10.0f * l.time[i], 1e-4f);  // x = x0 + v t
        if (i) {
            EXPECT_GT(l.time[i], l.time[i - 1]);
        }
    }
}

TEST(Tracer, StopsAtTheDomainBoundary) {
    const auto f = test::make_field({21, 11, 11}, [](glm::vec3) { return glm::vec3(10.0f, 0.0f, 0.0f); });
    const FlowSampler flow(f, false, std::nullopt);
    const TracedLine l = integrate_line(flow, {2.0f, 5.0f, 5.0f}, 0.0f, one_way(50.0f), 1e-3f);
    EXPECT_LE(l.position.back().x, 20.0f);
    EXPECT_GT(l.position.back().x, 19.5f);  // within one step of the wall
}

TEST(Tracer, SolidBodyRotationTracesACircleWithSmallRk4Error) {
    const glm::vec3 c(16.0f, 16.0f, 2.0f);
    const auto f = test::make_field({33, 33, 5}, [&](glm::vec3 p) { return glm::cross(glm::vec3(0, 0, 1), p - c); });
    const FlowSampler flow(f, false, std::nullopt);
    const float two_pi = 6.28318530718f;
    const TracedLine l = integrate_line(flow, c + glm::vec3(10, 0, 0), 0.0f, one_way(two_pi), 1e-3f);
    float worst = 0.0f;
    for (const auto& p : l.position) worst = std::max(worst, std::abs(glm::length(p - c) - 10.0f));
    EXPECT_LT(worst, 1e-3f);  // trilinear is exact for a linear field, so this is RK4 alone
    EXPECT_LT(glm::length(l.position.back() - l.position.front()), 1e-2f);  // closed after one turn
}

TEST(Tracer, InterpolatesLinearlyBetweenFramesAndWrapsPeriodically) {
    auto f = test::make_field({4, 4, 4}, [](glm::vec3) { return glm::vec3(1, 0, 0); });
    f.frames.push_back(std::vector<glm::vec3>(f.grid.count(), glm::vec3(3, 0, 0)));
    f.frame_times = {0.0f, 1.0f};
    const FlowSampler clamp(f, false, std::nullopt), wrap(f, true, std::nullopt);
    const glm::vec3 p(1.5f);
    EXPECT_NEAR(clamp.velocity(p, 0.5f).x, 2.0f, 1e-6f);
    EXPECT_NEAR(clamp.velocity(p, 5.0f).x, 3.0f, 1e-6f);
    EXPECT_NEAR(clamp.velocity(p, -1.0f).x, 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(f.cycle(), 2.0f);
    EXPECT_NEAR(wrap.velocity(p, 1.5f).x, 2.0f, 1e-6f);   // between the last frame and the first again
    EXPECT_NEAR(wrap.velocity(p, 2.25f).x, 1.5f, 1e-6f);  // 2.25 wraps to 0.25
    EXPECT_NEAR(wrap.velocity(p, -0.75f).x, 2.5f, 1e-6f);  // -0.75 wraps to 1.25

    // v = 1 + 2t for t in [0, 1]: x(1) = x0 + 2, which RK4 integrates exactly.
    auto big = test::make_field({40, 4, 4}, [](glm::vec3) { return glm::vec3(1, 0, 0); });
    big.frames.push_back(std::vector<glm::vec3>(big.grid.count(), glm::vec3(3, 0, 0)));
    big.frame_times = {0.0f, 1.0f};
    const TracedLine l = integrate_line(FlowSampler(big, false, std::nullopt), {5.0f, 1.5f, 1.5f}, 0.0f, one_way(1.0f), 1e-3f);
    EXPECT_NEAR(l.position.back().x, 7.0f, 1e-4f);
}

TEST(Tracer, PulsatileWaveformScalesVelocity) {
    Pulsatile p{0.8f, 3.0f};
    EXPECT_NEAR(p.factor(0.175f * 0.8f), 3.0f, 1e-4f);      // peak systole
    EXPECT_NEAR(p.factor(0.0f), 0.6f, 1e-5f);               // diastolic floor 0.2 * peak
    EXPECT_NEAR(p.factor(0.8f + 0.175f * 0.8f), 3.0f, 1e-4f);  // periodic
    float mean = 0.0f;
    for (int i = 0; i < 1000; ++i) mean += p.factor(0.8f * (i + 0.5f) / 1000.0f) / 1000.0f;
    EXPECT_NEAR(mean / 3.0f, 0.35f, 0.01f);
}

TEST(Tracer, EveryVesselVoxelIsCrossed) {
    const auto f = sphere_channel();
    TraceOptions o;
    o.time_end = 4.0f;
    TraceStats st;
    const Pathlines pl = trace_pathlines(f, o, {}, &st);
    ASSERT_FALSE(pl.empty());
    EXPECT_EQ(st.covered_voxels, st.vessel_voxels);
    const auto crossed = crossed_voxels(f.grid, pl);
    size_t missing = 0;
    for (size_t i = 0; i < f.grid.count(); ++i)
        if (f.inside_voxel(i) && !crossed.count(i)) ++missing;
    EXPECT_EQ(missing, 0u) << "of " << st.vessel_voxels << " vessel voxels";
    for (const auto& l : pl.lines)  // straight along x: smoothing keeps them straight
        for (uint32_t i = l.first; i < l.first + l.count; ++i) {
            EXPECT_NEAR(pl.position[i].y, pl.position[l.first].y, 1e-4f);
            EXPECT_GE(pl.time[i], 0.0f);
            EXPECT_LE(pl.time[i], 4.0f);
        }
}

TEST(Tracer, DropsShortAndCloseLines) {
    const auto f = sphere_channel();
    TraceOptions o;
    o.time_end = 4.0f;
    const Pathlines all = trace_pathlines(f, o);

    o.min_length = 10.0f;
    TraceStats st;
    const Pathlines longer = trace_pathlines(f, o, {}, &st);
    EXPECT_GT(st.rejected_short, 0u);
    for (const auto& l : longer.lines) {
        std::vector<glm::vec3> pts(longer.position.begin() + l.first, longer.position.begin() + l.first + l.count);
        EXPECT_GE(polyline_length(pts), 10.0f);
    }

    o.min_length = 0.0f;
    o.min_distance = 3.0f;
    const Pathlines sparse = trace_pathlines(f, o, {}, &st);
    EXPECT_GT(st.rejected_close, 0u);
    EXPECT_LT(sparse.line_count(), all.line_count() / 2);
    // Replaying the accepted lines in order: none ran alongside an earlier one.
    ProximityHash seen(3.0f);
    for (const auto& l : sparse.lines) {
        std::vector<glm::vec3> pts(sparse.position.begin() + l.first, sparse.position.begin() + l.first + l.count);
        EXPECT_LT(seen.near_fraction(pts), o.close_fraction);
        for (size_t i = 0; i + 1 < pts.size(); ++i)
            for (int k = 0; k < 4; ++k) seen.insert(pts[i] + (pts[i + 1] - pts[i]) * (k / 4.0f));
        seen.insert(pts.back());
    }
}

TEST(Tracer, BinomialSmoothingKeepsEndpointsAndReducesCurvature) {
    std::vector<glm::vec3> zig;
    for (int i = 0; i < 30; ++i) zig.push_back({float(i), (i % 2) ? 1.0f : -1.0f, 0.0f});
    auto turning = [](const std::vector<glm::vec3>& p) {
        float sum = 0.0f;
        for (size_t i = 1; i + 1 < p.size(); ++i)
            sum += std::acos(std::clamp(glm::dot(glm::normalize(p[i] - p[i - 1]), glm::normalize(p[i + 1] - p[i])), -1.0f, 1.0f));
        return sum;
    };
    auto smooth = zig;
    binomial_smooth(smooth, 3);
    EXPECT_EQ(smooth.front(), zig.front());
    EXPECT_EQ(smooth.back(), zig.back());
    EXPECT_LT(turning(smooth), 0.3f * turning(zig));
    // A straight line is a fixed point.
    std::vector<glm::vec3> line{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
    auto same = line;
    binomial_smooth(same, 5);
    EXPECT_EQ(same, line);
}

TEST(Tracer, ResamplesByArcLength) {
    TracedLine l;
    for (int i = 0; i <= 10; ++i) {
        l.position.push_back({float(i), 0, 0});
        l.time.push_back(0.1f * i);
        l.velocity.push_back({10, 0, 0});
    }
    const TracedLine r = resample_by_length(l, 0.25f);
    ASSERT_EQ(r.size(), 41u);
    EXPECT_NEAR(r.position[5].x, 1.25f, 1e-5f);
    EXPECT_NEAR(r.time[5], 0.125f, 1e-5f);
    EXPECT_NEAR(r.position.back().x, 10.0f, 1e-5f);
}

TEST(Tracer, ResultDoesNotDependOnThreadCount) {
    const glm::vec3 c(12.0f, 12.0f, 6.0f);
    auto f = test::make_field({25, 25, 13}, [&](glm::vec3 p) {
        return glm::cross(glm::vec3(0, 0, 1), p - c) + glm::vec3(0, 0, 0.5f * std::sin(p.x * 0.3f));
    });
    test::mask_sphere(f, c, 11.0f);
    TraceOptions o;
    o.time_end = 3.0f;
    o.min_length = 3.0f;
    o.min_distance = 1.5f;
    o.batch = 32;
    o.threads = 1;
    const Pathlines a = trace_pathlines(f, o);
    o.threads = 3;
    const Pathlines b = trace_pathlines(f, o);
    o.threads = 8;
    const Pathlines d = trace_pathlines(f, o);
    ASSERT_GT(a.line_count(), 5u);
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.time, b.time);
    EXPECT_EQ(a.velocity, d.velocity);
    EXPECT_EQ(a.position, d.position);
    ASSERT_EQ(a.lines.size(), d.lines.size());
}

TEST(Tracer, RejectsUnusableInput) {
    VelocityField empty;
    empty.source = "empty.vti";
    EXPECT_THROW(trace_pathlines(empty, {}), DataError);
    auto f = sphere_channel();
    TraceOptions o;
    o.time_end = o.time_begin;
    EXPECT_THROW(trace_pathlines(f, o), DataError);
}
