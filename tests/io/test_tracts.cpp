// Tractography inputs: TrackVis .trk (v1/v2, byte orders, voxel-to-RAS and voxel order,
// scalars and properties) and MRtrix .tck (four data types) read back what the writers wrote;
// streamlines load as timeless lines with a pseudo-time along the arc length; the fornix
// from ../shared/data/real. Bad tract files are in test_bad_input.cpp.
#include "io/pathline_io.hpp"
#include "io/tract_formats.hpp"
#include "io_test_util.hpp"

#include <algorithm>
#include <cmath>

using namespace pathlet;
using namespace pathlet::io;

namespace {

struct IoTracts : iotest::FileTest {
    static bool has(const LoadReport& r, const std::string& needle) { return iotest::reports(r, needle); }
    // Same lines and points within `tol` (the readers' repair step keeps every point here).
    static void expect_positions(const Pathlines& got, const Pathlines& want, float tol) {
        ASSERT_EQ(got.line_count(), want.line_count());
        ASSERT_EQ(got.point_count(), want.point_count());
        for (size_t i = 0; i < want.point_count(); ++i)
            ASSERT_LT(glm::length(got.position[i] - want.position[i]), tol) << "point " << i;
    }
};

TEST_F(IoTracts, TrkV2RoundTripThroughVoxelToRas) {
    Pathlines p = iotest::make_lines(4, 12);
    // A real scanner matrix: 2 mm voxels, x and y flipped (LPS voxel axes), shifted.
    TrkWriteOptions o;
    o.voxel_size = glm::vec3(2.0f);
    o.voxel_order = "LPS";
    o.vox_to_ras = glm::mat4(glm::vec4(-2, 0, 0, 0), glm::vec4(0, -2, 0, 0), glm::vec4(0, 0, 2, 0), glm::vec4(90, 120, -60, 1));
    LoadReport r;
    Pathlines q = load_pathlines(put("a.trk", write_trk(p, o)), {}, &r);
    EXPECT_EQ(r.format, "TrackVis .trk v2, little-endian, voxel-to-RAS");
    expect_positions(q, p, 1e-4f);
    EXPECT_EQ(q.units.length, "mm");
    EXPECT_TRUE(q.units.time.empty());
    EXPECT_TRUE(q.units.velocity.empty());
    EXPECT_TRUE(q.timeless);
}

TEST_F(IoTracts, TrkVoxelOrderDisagreeingWithTheMatrixFlipsThatAxis) {
    Pathlines p = iotest::make_lines(2, 6);
    TrkWriteOptions o;
    o.dims = {40, 50, 60};
    std::string b = write_trk(p, o);  // identity matrix, RAS
    b.replace(948, 3, "LAS");         // the file's x voxel axis now runs to the left
    Pathlines q = load_pathlines(put("a.trk", b));
    ASSERT_EQ(q.point_count(), p.point_count());
    for (size_t i = 0; i < p.point_count(); ++i) {
        EXPECT_NEAR(q.position[i].x, 39.0f - p.position[i].x, 1e-4f);  // (dim - 1) - index
        EXPECT_NEAR(q.position[i].y, p.position[i].y, 1e-4f);
        EXPECT_NEAR(q.position[i].z, p.position[i].z, 1e-4f);
    }
    // A voxel order that is no permutation of the axes is taken as the matrix's, said so.
    b.replace(948, 3, "RRS");
    LoadReport r;
    expect_positions(load_pathlines(put("b.trk", b), {}, &r), p, 1e-4f);
    EXPECT_TRUE(has(r, "voxel_order 'RRS' is not a permutation"));
}

TEST_F(IoTracts, TrkV1AndUnsetMatrixKeepVoxmm) {
    Pathlines p = iotest::make_lines(3, 8);
    TrkWriteOptions o;
    o.version = 1;
    LoadReport r;
    Pathlines q = load_pathlines(put("a.trk", write_trk(p, o)), {}, &r);
    EXPECT_EQ(r.format, "TrackVis .trk v1, little-endian, voxmm");
    expect_positions(q, p, 1e-5f);
    EXPECT_TRUE(has(r, "TrackVis v1 has no voxel-to-RAS matrix"));
    // v2 with vox_to_ras[3][3] = 0 ("not recorded"): the same.
    o.version = 2;
    o.vox_to_ras = glm::mat4(0.0f);
    LoadReport r2;
    std::string b = write_trk(p, o);
    expect_positions(load_pathlines(put("b.trk", b), {}, &r2), p, 1e-5f);
    EXPECT_TRUE(has(r2, "the header has no voxel-to-RAS matrix"));
}

TEST_F(IoTracts, TrkBigEndianWithScalarsAndProperties) {
    Pathlines p = iotest::make_lines(3, 10);
    TrkWriteOptions o;
    o.big_endian = true;
    o.scalars = 2;
    o.properties = 1;
    LoadReport r;
    Pathlines q = load_pathlines(put("a.trk", write_trk(p, o)), {}, &r);
    EXPECT_EQ(r.format, "TrackVis .trk v2, big-endian, voxel-to-RAS");
    expect_positions(q, p, 1e-4f);
    // Scalar k of point i is i + k/10, property k of track j is j + k/10 (write_trk).
    ASSERT_EQ(r.arrays.size(), 3u);
    EXPECT_EQ(r.arrays[0], "s0 (per point, 0 .. 11; not drawn)");
    EXPECT_EQ(r.arrays[1], "s1 (per point, 0.1 .. 11.1; not drawn)");
    EXPECT_EQ(r.arrays[2], "p0 (per track, 0 .. 2; not drawn)");
}

TEST_F(IoTracts, TrkNameSlotWithACountStandsForSeveralScalars) {
    Pathlines p = iotest::make_lines(2, 5);
    TrkWriteOptions o;
    o.scalars = 4;
    std::string b = write_trk(p, o);
    // Slot 0 "rgb" with 3 in its last byte, slot 1 "fa": four values per point.
    std::string slots(40, '\0');
    slots.replace(0, 3, "rgb");
    slots[19] = 3;
    slots.replace(20, 2, "fa");
    b.replace(38, 40, slots);
    LoadReport r;
    expect_positions(load_pathlines(put("a.trk", b), {}, &r), p, 1e-4f);
    ASSERT_EQ(r.arrays.size(), 2u);
    EXPECT_EQ(r.arrays[0], "rgb (per point, 3 comp, 0 .. 5.2; not drawn)");
    EXPECT_EQ(r.arrays[1], "fa (per point, 0.3 .. 5.3; not drawn)");
}

TEST_F(IoTracts, TckRoundTripEveryDataType) {
    Pathlines p = iotest::make_lines(5, 9);
    for (bool big : {false, true})
        for (bool f64 : {false, true}) {
            LoadReport r;
            Pathlines q = load_pathlines(put("a.tck", write_tck(p, {.big_endian = big, .float64 = f64})), {}, &r);
            EXPECT_EQ(r.format, std::string("MRtrix .tck, Float") + (f64 ? "64" : "32") + (big ? "BE" : "LE"));
            expect_positions(q, p, 1e-6f);
            EXPECT_EQ(q.units.length, "mm");
            EXPECT_TRUE(q.timeless);
        }
}

TEST_F(IoTracts, StreamlinesGetAPseudoTimeAlongTheArcAndOneSpeed) {
    Pathlines p;
    p.lines = {{0, 3}, {3, 2}};
    p.position = {{0, 0, 0}, {3, 0, 0}, {3, 4, 0}, {0, 0, 10}, {0, 0, 12}};
    LoadReport r;
    Pathlines q = load_pathlines(put("a.tck", write_tck(p)), {}, &r);
    ASSERT_EQ(q.point_count(), 5u);
    // Diagonal of (0,0,0)-(3,4,12) is 13: pseudo-speed 1.3 per second.
    EXPECT_NEAR(q.time[0], 0.0f, 1e-6f);
    EXPECT_NEAR(q.time[1], 3.0f / 1.3f, 1e-5f);
    EXPECT_NEAR(q.time[2], 7.0f / 1.3f, 1e-5f);
    EXPECT_NEAR(q.time[3], 0.0f, 1e-6f);  // every line starts at 0
    EXPECT_NEAR(q.time[4], 2.0f / 1.3f, 1e-5f);
    for (auto& v : q.velocity) EXPECT_NEAR(glm::length(v), 1.3f, 1e-5f);
    EXPECT_NEAR(q.velocity[3].z, 1.3f, 1e-5f);  // along the line
    EXPECT_TRUE(q.timeless);
    EXPECT_TRUE(has(r, "streamlines, drawn whole"));
    // --pseudo-time: the same lines, animated.
    LoadOptions o;
    o.pseudo_time = true;
    Pathlines a = load_pathlines(put("a.tck", write_tck(p)), o);
    EXPECT_FALSE(a.timeless);
    EXPECT_EQ(a.time, q.time);
}

TEST_F(IoTracts, VtkLinesWithoutTimeNeedTheStreamlinesOption) {
    const std::string vtk = "# vtk DataFile Version 4.2\nc\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 2 1 0\n"
                            "LINES 1 4\n3 0 1 2\n";
    const std::string path = put("c.vtk", vtk);
    EXPECT_THROW(load_pathlines(path), DataError);
    LoadOptions o;
    o.streamlines = true;
    Pathlines q = load_pathlines(path, o);
    EXPECT_TRUE(q.timeless);
    ASSERT_EQ(q.point_count(), 3u);
    EXPECT_GT(q.time[2], q.time[1]);
}

TEST_F(IoTracts, RealFornixTrackVis) {
    const std::string d = iotest::real_data_dir();
    if (d.empty()) GTEST_SKIP() << "real data absent (../shared/data/real): fornix-tractography/tracks300.trk not checked";
    LoadReport r;
    Pathlines q = load_pathlines(d + "/fornix-tractography/tracks300.trk", {}, &r);
    EXPECT_EQ(r.format, "TrackVis .trk v2, little-endian, voxel-to-RAS");
    EXPECT_EQ(q.line_count(), 300u);
    EXPECT_EQ(q.point_count(), 14576u);
    EXPECT_TRUE(q.timeless);
    EXPECT_EQ(q.units.length, "mm");
    // The README's voxmm bounds less TrackVis's half-voxel corner offset (1 mm voxels, identity matrix).
    Bounds b = q.bounds();
    EXPECT_NEAR(b.lo.x, 64.0f, 0.05f);
    EXPECT_NEAR(b.lo.y, 78.4f, 0.05f);
    EXPECT_NEAR(b.lo.z, 61.5f, 0.05f);
    EXPECT_NEAR(b.hi.x, 115.6f, 0.05f);
    EXPECT_NEAR(b.hi.y, 121.1f, 0.05f);
    EXPECT_NEAR(b.hi.z, 91.9f, 0.05f);
    auto counts = std::minmax_element(q.lines.begin(), q.lines.end(),
                                      [](const LineRange& a, const LineRange& c) { return a.count < c.count; });
    EXPECT_EQ(counts.first->count, 30u);
    EXPECT_EQ(counts.second->count, 91u);
}

}  // namespace
