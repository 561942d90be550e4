// Marching cubes: generated table sanity, closed and consistently wound surfaces, sphere area.
#include "field_fixtures.hpp"

#include "trace/hash_random.hpp"
#include "trace/marching_cubes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

using namespace pathlet;
using namespace pathlet::trace;

namespace {

// Every directed edge must appear once and its reverse once: closed, consistently wound.
void expect_closed_and_consistent(const Mesh& m) {
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (size_t t = 0; t < m.index.size(); t += 3)
        for (int e = 0; e < 3; ++e) ++directed[{m.index[t + e], m.index[t + (e + 1) % 3]}];
    size_t bad = 0;
    for (const auto& [edge, n] : directed) {
        auto rev = directed.find({edge.second, edge.first});
        if (n != 1 || rev == directed.end() || rev->second != 1) ++bad;
    }
    EXPECT_EQ(bad, 0u) << "of " << directed.size() << " directed edges";
}

double area(const Mesh& m) {
    double a = 0.0;
    for (size_t t = 0; t < m.index.size(); t += 3)
        a += 0.5 * glm::length(glm::cross(m.position[m.index[t + 1]] - m.position[m.index[t]],
                                          m.position[m.index[t + 2]] - m.position[m.index[t]]));
    return a;
}

double volume(const Mesh& m) {  // divergence theorem; positive when normals point outward
    double v = 0.0;
    for (size_t t = 0; t < m.index.size(); t += 3)
        v += glm::dot(m.position[m.index[t]], glm::cross(m.position[m.index[t + 1]], m.position[m.index[t + 2]])) / 6.0;
    return v;
}

}  // namespace

TEST(MarchingCubes, TableIsComplete) {
    const auto& t = mc_table();
    EXPECT_TRUE(t[0].tris.empty());
    EXPECT_TRUE(t[255].tris.empty());
    for (int c = 1; c < 255; ++c) {
        EXPECT_FALSE(t[c].tris.empty()) << c;
        EXPECT_LE(t[c].tris.size(), 12u) << c;
    }
    EXPECT_EQ(t[1].tris.size(), 1u);    // one corner
    EXPECT_EQ(t[0x0f].tris.size(), 2u);  // a face's worth: one quad
}

TEST(MarchingCubes, SphereIsClosedOutwardAndHasTheRightArea) {
    trace::Grid g;
    g.dims = {28, 28, 28};
    g.spacing = glm::vec3(1.0f);
    g.origin = glm::vec3(-13.5f);
    const float r = 10.0f;
    const Mesh m = marching_cubes(g, test::sphere_values(g, glm::vec3(0.3f, -0.2f, 0.1f), r), 0.0f);
    ASSERT_FALSE(m.empty());
    EXPECT_EQ(m.normal.size(), m.position.size());
    expect_closed_and_consistent(m);
    const double pi = 3.14159265358979;
    EXPECT_NEAR(area(m) / (4.0 * pi * r * r), 1.0, 0.03);
    EXPECT_NEAR(volume(m) / (4.0 / 3.0 * pi * r * r * r), 1.0, 0.03);
    for (size_t i = 0; i < m.position.size(); ++i) {
        EXPECT_NEAR(glm::length(m.position[i] - glm::vec3(0.3f, -0.2f, 0.1f)), r, 0.1f);
        EXPECT_GT(glm::dot(m.normal[i], glm::normalize(m.position[i] - glm::vec3(0.3f, -0.2f, 0.1f))), 0.9f);
    }
}

TEST(MarchingCubes, RandomFieldsGiveClosedConsistentSurfaces) {
    // Noise exercises every ambiguous configuration; a zero border keeps the surface inside.
    trace::Grid g;
    g.dims = {14, 13, 12};
    for (uint64_t seed = 1; seed <= 5; ++seed) {
        std::vector<float> v(g.count(), 0.0f);
        for (size_t i = 0; i < g.count(); ++i) {
            const glm::ivec3 c = g.coord(i);
            const bool border = glm::any(glm::equal(c, glm::ivec3(0))) || glm::any(glm::equal(c, g.dims - 1));
            v[i] = border ? 0.0f : unit_float(hash64(i, seed));
        }
        const Mesh m = marching_cubes(g, v, 0.5f);
        ASSERT_FALSE(m.empty());
        expect_closed_and_consistent(m);
        EXPECT_GT(volume(m), 0.0);
    }
}

TEST(MarchingCubes, BinaryMaskMergesVerticesAndRejectsWrongSizes) {
    trace::Grid g;
    g.dims = {6, 6, 6};
    std::vector<float> v(g.count(), 0.0f);
    v[g.index(2, 2, 2)] = v[g.index(3, 2, 2)] = 1.0f;
    const Mesh m = marching_cubes(g, v, 0.5f);
    expect_closed_and_consistent(m);
    EXPECT_EQ(m.position.size(), 10u);  // 2 points x 6 axis edges, minus the one edge between them
    EXPECT_THROW(marching_cubes(g, std::vector<float>(5), 0.5f), DataError);
}

TEST(MarchingCubes, SmallPiecesDropWithTheirVerticesLargeOnesStay) {
    // Three balls in one volume: radius 9 (the largest), 5 and a speck of 1.2.
    trace::Grid g;
    g.dims = {48, 24, 24};
    g.spacing = glm::vec3(1.0f);
    g.origin = glm::vec3(0.0f);
    std::vector<float> v(g.count());
    const glm::vec3 c[3] = {{12, 12, 12}, {32, 12, 12}, {43, 5, 5}};
    const float r[3] = {9.0f, 5.0f, 1.2f};
    for (size_t i = 0; i < g.count(); ++i) {
        const glm::vec3 p = g.point(g.coord(i));
        float best = -1e9f;
        for (int k = 0; k < 3; ++k) best = std::max(best, r[k] - glm::length(p - c[k]));
        v[i] = best;
    }
    const Mesh all = marching_cubes(g, v, 0.0f);
    PieceStats st;
    const Mesh kept = drop_small_pieces(all, 0.05f, &st);
    EXPECT_EQ(st.pieces, 3u);
    EXPECT_EQ(st.kept, 2u);
    EXPECT_GT(st.dropped_triangles, 0u);
    EXPECT_EQ(kept.index.size() + 3 * st.dropped_triangles, all.index.size());
    expect_closed_and_consistent(kept);  // whole pieces go, the rest keeps its winding
    EXPECT_EQ(kept.normal.size(), kept.position.size());
    std::vector<bool> used(kept.position.size(), false);
    for (uint32_t i : kept.index) used[i] = true;
    EXPECT_EQ(std::count(used.begin(), used.end(), false), 0) << "vertices only the speck used must go";
    for (const auto& p : kept.position) EXPECT_GT(glm::length(p - c[2]), 2.0f) << "a speck vertex survived";
    // 0 keeps everything; a share above the second ball keeps only the largest.
    EXPECT_EQ(drop_small_pieces(all, 0.0f).index.size(), all.index.size());
    drop_small_pieces(all, 0.5f, &st);
    EXPECT_EQ(st.kept, 1u);
}
