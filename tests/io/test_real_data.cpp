// Real third-party data (shared/data/real); skipped when the directory is absent.
#include "io/file_info.hpp"
#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
#include "io_test_util.hpp"

#include <algorithm>
#include <filesystem>

using namespace pathlet;
using namespace pathlet::io;

namespace {

std::string real(const std::string& rel) {
    std::string d = iotest::real_data_dir();
    if (d.empty() || !std::filesystem::exists(d + "/" + rel)) return "";
    return d + "/" + rel;
}

#define REAL_OR_SKIP(var, rel)                                  \
    std::string var = real(rel);                                \
    if (var.empty()) GTEST_SKIP() << rel << ": real data absent"

bool has_warning(const LoadReport& r, const std::string& needle) {
    for (auto& w : r.warnings)
        if (w.find(needle) != std::string::npos) return true;
    return false;
}

TEST(IoRealData, AneurysmBloodFlowTextRows) {
    REAL_OR_SKIP(path, "aneurysm-pathlines/blood_flow");
    LoadReport r;
    Pathlines p = load_pathlines(path, {}, &r);
    EXPECT_EQ(r.format, "plain-text pathline rows");
    EXPECT_EQ(p.line_count(), 547u);
    // 148,727 raw samples; 95,250 leading seed copies (late release) are dropped.
    EXPECT_TRUE(has_warning(r, "late release: dropped 95250 leading copies")) << r.warnings.size();
    EXPECT_TRUE(has_warning(r, "148727 raw samples"));
    EXPECT_EQ(p.point_count(), 53477u);  // moving samples; no other duplicates in this file
    // Derived times: sample k at k * 0.01 s, so a line released after 349 steps starts at 3.49 s.
    EXPECT_FLOAT_EQ(p.time_min(), 0.0f);
    EXPECT_NEAR(p.time_max(), 6.44f, 1e-3f);  // the longest row has 645 samples
    float latest_start = 0.0f;
    for (auto& l : p.lines) latest_start = std::max(latest_start, p.time[l.first]);
    EXPECT_NEAR(latest_start, 3.49f, 1e-4f);
    // Velocity by finite differences: step lengths up to 2.15 file units per 0.01 s.
    EXPECT_GT(p.speed_max(), 100.0f);
    EXPECT_LT(p.speed_max(), 300.0f);
    Bounds b = p.bounds();
    EXPECT_NEAR(b.lo.x, -8.44f, 0.01f);
    EXPECT_NEAR(b.hi.z, 10.53f, 0.01f);
    // time_step option scales time.
    LoadOptions o;
    o.time_step = 0.005;
    Pathlines q = load_pathlines(path, o);
    EXPECT_NEAR(q.time_max(), 3.22f, 1e-3f);
}

TEST(IoRealData, AortaSurfaceStl) {
    REAL_OR_SKIP(path, "vmtk-abdominal-aorta/aorta-surface.stl");
    LoadReport r;
    Mesh m = load_mesh(path, &r);
    EXPECT_EQ(r.format, "STL binary");
    // STL stores 3 corners per facet (38,796); merging identical corners gives the
    // surface's real 6,468 vertices (the same count the .vtp of this mesh declares).
    EXPECT_EQ(m.position.size(), 6468u);
    EXPECT_EQ(m.index.size() / 3, 12932u);
    EXPECT_EQ(m.normal.size(), m.position.size());
    Bounds b = m.bounds();
    EXPECT_NEAR(b.lo.x, 205.6f, 0.1f);
    EXPECT_NEAR(b.hi.y, 181.6f, 0.1f);
    EXPECT_NEAR(b.hi.z, 35.4f, 0.1f);
}

TEST(IoRealData, AortaSurfaceVtpIsPolygonsNotLines) {
    REAL_OR_SKIP(path, "vmtk-abdominal-aorta/aorta-surface.vtp");
    try {
        load_pathlines(path);
        FAIL() << "expected DataError";
    } catch (const DataError& e) {
        std::string m = e.what();
        EXPECT_EQ(m.rfind(path + ": byte ", 0), 0u) << m;
        EXPECT_NE(m.find("12932 polygons and no lines"), std::string::npos) << m;
        EXPECT_NE(m.find("mesh"), std::string::npos) << m;
    }
}

TEST(IoRealData, AortaCenterlineVtpHasNoTime) {
    REAL_OR_SKIP(path, "vmtk-abdominal-aorta/aorta-centerline.vtp");
    try {
        load_pathlines(path);
        FAIL() << "expected DataError";
    } catch (const DataError& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("MaximumInscribedSphereRadius (1 comp)"), std::string::npos) << m;
        EXPECT_NE(m.find("--time-array"), std::string::npos) << m;
    }
    // Naming the radius as "time" is nonsense physically but proves the option path works.
    LoadOptions o;
    o.time_array = "MaximumInscribedSphereRadius";
    LoadReport r;
    Pathlines p = load_pathlines(path, o, &r);
    ASSERT_GE(p.line_count(), 1u);
    EXPECT_GE(p.point_count(), 2 * p.line_count());
    // The chosen array became the time: positive radii, increasing along each (repaired) line.
    for (const auto& l : p.lines)
        for (uint32_t k = 1; k < l.count; ++k) ASSERT_GT(p.time[l.first + k], p.time[l.first + k - 1]);
    EXPECT_GT(*std::min_element(p.time.begin(), p.time.end()), 0.0f);
    EXPECT_NE(r.format.find("zlib"), std::string::npos) << r.format;
}

TEST(IoRealData, CarotidStructuredPointsRejectedClearly) {
    REAL_OR_SKIP(path, "carotid-vtk/carotid.vtk");
    try {
        load_pathlines(path);
        FAIL() << "expected DataError";
    } catch (const DataError& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("STRUCTURED_POINTS is not supported"), std::string::npos) << m;
    }
}

TEST(IoRealData, DescribeRealFiles) {
    REAL_OR_SKIP(path, "aneurysm-pathlines/blood_flow");
    std::string s = describe_file(path);
    EXPECT_NE(s.find("lines:     547"), std::string::npos) << s;
    EXPECT_NE(s.find("points per line: min"), std::string::npos) << s;
}

}  // namespace
