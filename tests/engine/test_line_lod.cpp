// The lines' level of detail (pathlet/line_lod.hpp): what a tolerance keeps, and the bound
// that makes it safe to draw (every dropped point within the tolerance of the drawn segment
// at its own time, speed within the colour tolerance).
#include <pathlet/line_lod.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace pathlet;

namespace {

Pathlines one_line(const std::vector<glm::vec3>& p, const std::vector<float>& t, const std::vector<float>& speed) {
    Pathlines pl;
    pl.position = p;
    pl.time = t;
    for (float s : speed) pl.velocity.push_back(glm::vec3(s, 0, 0));
    pl.lines.push_back({0, uint32_t(p.size())});
    return pl;
}

// n points one unit apart along x, one second apart, speed 1: every interior point on the chord.
Pathlines straight_line(int n) {
    std::vector<glm::vec3> p;
    std::vector<float> t, s;
    for (int i = 0; i < n; ++i) p.push_back({float(i), 0, 0}), t.push_back(float(i)), s.push_back(1.0f);
    return one_line(p, t, s);
}

LineLod built(const Pathlines& pl, float speed_range = 1.0f) {
    LineLod lod;
    lod.build(pl, speed_range);
    return lod;
}

LineLod::Strips select_all(const LineLod& lod, const Pathlines& pl, float eps) {
    std::vector<GLint> first;
    std::vector<GLsizei> count;
    std::vector<uint32_t> line;
    for (size_t i = 0; i < pl.lines.size(); ++i) {
        first.push_back(GLint(pl.lines[i].first));
        count.push_back(GLsizei(pl.lines[i].count));
        line.push_back(uint32_t(i));
    }
    LineLod::Strips s;
    lod.select(first, count, line, glm::vec3(0), eps, /*perspective=*/false, 1.0f, s);
    return s;
}

}  // namespace

TEST(LineLod, AStraightUniformLineKeepsOnlyItsEnds) {
    Pathlines pl = straight_line(1000);
    LineLod lod = built(pl);
    LineLod::Strips st = select_all(lod, pl, 1e-3f);
    ASSERT_EQ(st.count.size(), 1u);
    EXPECT_EQ(st.count[0], 2);
    EXPECT_EQ(st.index[0], 0u);
    EXPECT_EQ(st.index[1], 999u);
    EXPECT_EQ(st.segments, 1u);
}

TEST(LineLod, AZigzagIsKeptBelowItsAmplitudeAndDroppedAbove) {
    std::vector<glm::vec3> p;
    std::vector<float> t, s;
    for (int i = 0; i <= 100; ++i) p.push_back({float(i), (i % 2) ? 0.5f : 0.0f, 0}), t.push_back(float(i)), s.push_back(1);
    Pathlines pl = one_line(p, t, s);
    LineLod lod = built(pl);
    EXPECT_EQ(select_all(lod, pl, 0.2f).segments, 100u);  // every point matters
    EXPECT_EQ(select_all(lod, pl, 0.6f).segments, 1u);    // a band 0.5 wide fits a chord at 0.6
}

// Time is part of the error: a point where the particle lingers (same place, later time) is
// kept, or the time-window clip would jump along the line.
TEST(LineLod, AStraightLineWithUnevenTimeKeepsThePointsTheClipNeeds) {
    std::vector<glm::vec3> p;
    std::vector<float> t, s;
    for (int i = 0; i <= 10; ++i) p.push_back({float(i), 0, 0}), s.push_back(1);
    t = {0, 1, 2, 3, 4, 9, 10, 11, 12, 13, 14};  // slow between points 4 and 5
    Pathlines pl = one_line(p, t, s);
    LineLod lod = built(pl);
    EXPECT_GT(select_all(lod, pl, 0.5f).segments, 1u);
}

TEST(LineLod, SpeedChangesBeyondTheColourToleranceAreKeptAtAnyZoom) {
    std::vector<glm::vec3> p;
    std::vector<float> t, s;
    for (int i = 0; i <= 20; ++i) p.push_back({float(i), 0, 0}), t.push_back(float(i)), s.push_back(i == 10 ? 2.0f : 1.0f);
    Pathlines pl = one_line(p, t, s);
    LineLod lod = built(pl, 10.0f);  // the bump is 10 % of the colour range
    LineLod::Strips st = select_all(lod, pl, 1e6f);
    EXPECT_NE(std::find(st.index.begin(), st.index.end(), 10u), st.index.end());
}

// The property the renderer relies on, on random smooth curves: at every tolerance, each
// dropped point lies within eps of the kept segment around it, evaluated at its own time.
TEST(LineLod, EveryDroppedPointIsWithinTheToleranceOfItsSegmentAtItsTime) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Pathlines pl;
    for (int li = 0; li < 20; ++li) {
        uint32_t first = uint32_t(pl.position.size());
        glm::vec3 x(0), v(1, 0, 0);
        float time = 0;
        for (int i = 0; i < 300; ++i) {
            v = glm::normalize(v + 0.2f * glm::vec3(u(rng), u(rng), u(rng)));
            x += 0.1f * v;
            time += 0.05f * (1.5f + 0.5f * std::sin(0.1f * float(i)));  // smooth, as traced data is
            pl.position.push_back(x);
            pl.time.push_back(time);
            pl.velocity.push_back(v * (1.0f + 0.2f * std::sin(0.05f * float(i + li))));
        }
        pl.lines.push_back({first, 300});
    }
    LineLod lod = built(pl);
    for (float eps : {0.001f, 0.01f, 0.05f, 0.2f}) {
        LineLod::Strips st = select_all(lod, pl, eps);
        size_t k = 0;
        for (size_t li = 0; li < st.count.size(); ++li) {
            for (GLsizei j = 0; j + 1 < st.count[li]; ++j) {
                const uint32_t a = st.index[k + size_t(j)], b = st.index[k + size_t(j) + 1];
                for (uint32_t m = a + 1; m < b; ++m) {
                    const float f = (pl.time[m] - pl.time[a]) / (pl.time[b] - pl.time[a]);
                    const glm::vec3 on = glm::mix(pl.position[a], pl.position[b], f);
                    ASSERT_LE(glm::length(pl.position[m] - on), eps * 1.0001f) << "eps " << eps << " point " << m;
                    const float sa = glm::length(pl.velocity[a]), sb = glm::length(pl.velocity[b]);
                    ASSERT_LE(std::fabs(glm::length(pl.velocity[m]) - glm::mix(sa, sb, f)),
                              LineLod::kSpeedTolerance * 1.0001f);
                }
            }
            k += size_t(st.count[li]);
        }
        if (eps >= 0.05f) { EXPECT_LT(st.segments, 20u * 299u / 2) << "eps " << eps << " simplifies little"; }
    }
}

// A window's range is widened to the kept points around it, so the kit's time clip still
// reaches the window's ends exactly.
TEST(LineLod, AWindowedRangeIsBracketedByKeptPoints) {
    Pathlines pl = straight_line(100);
    LineLod lod = built(pl);
    LineLod::Strips st;
    lod.select({40}, {10}, {0}, glm::vec3(0), 1.0f, false, 0.5f, st);
    ASSERT_EQ(st.count.size(), 1u);
    EXPECT_LE(st.index.front(), 40u);
    EXPECT_GE(st.index.back(), 49u);
}

// A pass with a width hook asks for at most 16 data segments per drawn segment.
TEST(LineLod, MaxSkipBoundsTheDataSegmentsPerDrawnSegment) {
    Pathlines pl = straight_line(1000);
    LineLod lod = built(pl);
    LineLod::Strips st;
    lod.select({0}, {1000}, {0}, glm::vec3(0), 1.0f, false, 0.5f, st, 16);
    for (size_t k = 0; k + 1 < st.index.size(); ++k) ASSERT_LE(st.index[k + 1] - st.index[k], 16u);
    EXPECT_EQ(st.segments, (999u + 15u) / 16u);
}

// A line of non-finite points has no bounding box (distance inf) and a broken camera gives NaN:
// the scans must still stop at the line's own ends and draw it whole.
TEST(LineLod, NonFiniteDistancesStayInsideTheLine) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    Pathlines pl;
    for (int li = 0; li < 2; ++li)
        for (int i = 0; i < 50; ++i) {
            pl.position.push_back(li == 1 ? glm::vec3(nan) : glm::vec3(float(i), 0, 0));
            pl.time.push_back(float(i));
            pl.velocity.push_back({1, 0, 0});
        }
    pl.lines = {{0, 50}, {50, 50}};
    LineLod lod = built(pl);
    for (glm::vec3 eye : {glm::vec3(0, 0, 10), glm::vec3(nan)}) {
        LineLod::Strips st;
        lod.select({0, 50}, {50, 50}, {0, 1}, eye, 1.0f, /*perspective=*/true, 0.5f, st);
        ASSERT_EQ(st.count.size(), 2u);
        for (size_t k = 0; k < size_t(st.count[0]); ++k) EXPECT_LT(st.index[k], 50u);
        for (size_t k = size_t(st.count[0]); k < st.index.size(); ++k) {
            EXPECT_GE(st.index[k], 50u);
            EXPECT_LT(st.index[k], 100u);
        }
    }
}
