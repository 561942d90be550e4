// opacity_lists' segmentation on the CPU: segment counts and lengths from the arc length, the
// mean of a field over each segment, and the buffer layout of shaders/opacity_optimization.glsl.
#include "../segmentation.hpp"

#include <gtest/gtest.h>

#include <cstring>

using namespace opacity_lists;

namespace {

// One straight line of `n` points, 1 unit apart along x, and one of 2 points 0.4 long.
pathlet::Pathlines two_lines(int n) {
    pathlet::Pathlines pl;
    pl.lines.push_back({0, uint32_t(n)});
    for (int k = 0; k < n; ++k) pl.position.push_back({float(k), 0, 0});
    pl.lines.push_back({uint32_t(n), 2});
    pl.position.push_back({0, 5, 0});
    pl.position.push_back({0.4f, 5, 0});
    pl.time.assign(pl.position.size(), 0.0f);
    pl.velocity.assign(pl.position.size(), glm::vec3(0.0f));
    return pl;
}

}  // namespace

TEST(Segmentation, CutsEveryLineByArcLengthIntoEqualSegments) {
    const pathlet::Pathlines pl = two_lines(11);  // 10 units long
    const std::vector<float> arc = arc_lengths(pl);
    EXPECT_FLOAT_EQ(arc[10], 10.0f);
    const Segmentation s = segment_lines(pl, arc, 3.0f);
    ASSERT_EQ(s.first.size(), 2u);
    EXPECT_EQ(s.count[0], 3u);                // 10 / 3 rounded
    EXPECT_FLOAT_EQ(s.length[0], 10.0f / 3);  // equal pieces over the whole line
    EXPECT_EQ(s.count[1], 1u);                // a short line keeps one segment
    EXPECT_EQ(s.first[1], 3u);
    EXPECT_EQ(s.line, (std::vector<uint32_t>{0, 0, 0, 1}));
}

TEST(Segmentation, MeanOfALinearFieldIsItsValueAtTheSegmentCentre) {
    const pathlet::Pathlines pl = two_lines(11);
    const std::vector<float> arc = arc_lengths(pl);
    const Segmentation s = segment_lines(pl, arc, 2.5f);  // 4 segments of 2.5
    std::vector<float> field(pl.position.size());
    for (size_t i = 0; i < field.size(); ++i) field[i] = 3.0f * pl.position[i].x + 1.0f;
    const std::vector<float> m = segment_means(pl, arc, s, field);
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(m[j], 3.0f * (2.5f * j + 1.25f) + 1.0f, 1e-4) << "segment " << j;
    // A step in the field: the mean weighs each side by its length.
    for (size_t i = 0; i < 11; ++i) field[i] = i < 5 ? 0.0f : 1.0f;
    const std::vector<float> step = segment_means(pl, arc, s, field);
    EXPECT_NEAR(step[1], (0.0 * 1.5 + 0.5 * 1.0) / 2.5, 1e-5);  // [2.5, 5]: 0 up to 4, then 0 -> 1 over [4, 5]
}

TEST(Segmentation, PackedAsTheShadersReadIt) {
    const pathlet::Pathlines pl = two_lines(11);
    const std::vector<float> arc = arc_lengths(pl);
    const Segmentation s = segment_lines(pl, arc, 3.0f);
    const std::vector<float> g{0.1f, 0.2f, 0.3f, 0.4f};
    const std::vector<uint32_t> b = pack(s, 7, &g);
    ASSERT_EQ(b.size(), kHeaderWords + 4 * 2 + 4 + 4);
    EXPECT_EQ(b[0], 2u);
    EXPECT_EQ(b[1], 4u);
    EXPECT_EQ(b[2], 7u);
    EXPECT_EQ(b[3], kHeaderWords + 8);
    EXPECT_EQ(b[4], 1u);  // work groups of 64 over max(segments, the header and line table)
    EXPECT_EQ(b[8 + 4], 3u);  // line 1: first segment
    float len = 0, imp = 0;
    std::memcpy(&len, &b[8 + 2], 4);
    EXPECT_FLOAT_EQ(len, 10.0f / 3);
    EXPECT_EQ(b[b[3] + 3], 1u);  // segment 3's line
    std::memcpy(&imp, &b[b[3] + 4 + 2], 4);
    EXPECT_FLOAT_EQ(imp, 0.3f);
}

TEST(Segmentation, QuantileIgnoresNonFiniteValues) {
    std::vector<float> v;
    for (int i = 0; i <= 100; ++i) v.push_back(float(i));
    v.push_back(NAN);
    v.push_back(INFINITY);
    EXPECT_FLOAT_EQ(quantile(v, 0.01), 1.0f);
    EXPECT_FLOAT_EQ(quantile(v, 0.99), 99.0f);
}
