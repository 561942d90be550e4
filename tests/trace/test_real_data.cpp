// The real velocity volumes in shared/data/real (skipped when the folder is absent).
#include "trace/field_readers.hpp"
#include "trace/marching_cubes.hpp"
#include "trace/tracer.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

using namespace pathlet;
using namespace pathlet::trace;

namespace {

std::string real_file(const std::string& rel) {
    const char* env = std::getenv("PATHLET_REAL_DATA_DIR");
    const std::string dir = env && *env ? env : PATHLET_SOURCE_DIR "/../shared/data/real";
    return dir + "/" + rel;
}

#define REQUIRE_REAL(path)                                                                          \
    if (!std::filesystem::exists(path))                                                             \
        GTEST_SKIP() << "real data not found: " << path << " (set PATHLET_REAL_DATA_DIR to shared/data/real)"

TraceOptions coarse() {
    TraceOptions o;
    o.step = 0.5f;
    o.time_end = 5.0f;
    o.max_line_time = 3.0f;
    o.min_length = 5.0f;
    o.min_distance = 2.0f;
    o.batch = 512;
    return o;
}

void expect_inside(const Pathlines& pl, const Grid& g) {
    const Bounds b = g.bounds();
    for (const auto& p : pl.position) {
        ASSERT_TRUE(glm::all(glm::greaterThanEqual(p, b.lo - 1e-3f)) && glm::all(glm::lessThanEqual(p, b.hi + 1e-3f)));
    }
}

}  // namespace

TEST(RealData, CarotidVtkTracesInsideTheVessel) {
    const std::string path = real_file("carotid-vtk/carotid.vtk");
    REQUIRE_REAL(path);
    VelocityField f = load_velocity_field(path);
    EXPECT_EQ(f.grid.dims, glm::ivec3(76, 49, 45));
    EXPECT_EQ(f.grid.origin, glm::vec3(100, 80, 1));
    EXPECT_EQ(f.scalars_name, "scalars");
    f.mask_from_scalars(175.0f);
    EXPECT_GT(f.vessel_voxels(), 1000u);
    TraceStats st;
    const Pathlines pl = trace_pathlines(f, coarse(), {}, &st);
    EXPECT_GT(pl.line_count(), 20u);
    EXPECT_EQ(pl.position.size(), pl.time.size());
    expect_inside(pl, f.grid);
    // Units undocumented: none shown but the tracer's clock.
    EXPECT_EQ(pl.units, (Units{"", "s", ""}));
    const Mesh wall = marching_cubes(f.grid, f.scalars, 175.0f);
    EXPECT_NEAR(double(wall.index.size() / 3), 13.8e3, 0.05 * 13.8e3);  // README: 13.8k triangles at 175
    // The wall `pathlet trace --wall` writes: the noise specks of the threshold dropped, the
    // vessel (largest piece 5.2k triangles, README) and its branches kept.
    PieceStats pieces;
    const Mesh kept = vessel_wall(f, 0.01f, &pieces);
    EXPECT_GT(pieces.pieces, 20u);
    EXPECT_LT(pieces.kept, pieces.pieces / 2);
    EXPECT_GT(kept.index.size() / 3, 12000u);
}

TEST(RealData, FlowNetAorticArchTracesAndWalls) {
    const std::string path = real_file("aortic-arch-cfd-4dflownet/example_data_HR.h5");
    REQUIRE_REAL(path);
    const VelocityField f = load_velocity_field(path);
    EXPECT_EQ(f.grid.dims, glm::ivec3(72, 76, 84));
    EXPECT_NEAR(f.grid.spacing.x, 0.59375f, 1e-6f);
    EXPECT_EQ(f.vessel_voxels(), 56226u);  // README: 56,226 voxels > 0.5 (ours: >= 0.5)
    EXPECT_LT(f.max_speed(), 1000.0f);     // |v| max ~0.85 m/s, in mm/s
    EXPECT_GT(f.max_speed(), 500.0f);
    const Mesh wall = marching_cubes(f.grid, f.mask, 0.5f);
    EXPECT_NEAR(double(wall.index.size() / 3), 27.4e3, 0.03 * 27.4e3);
    TraceOptions o = coarse();
    o.time_end = 1.0f;
    o.max_line_time = 0.5f;
    o.min_distance = 1.5f;
    const Pathlines pl = trace_pathlines(f, o);
    EXPECT_GT(pl.line_count(), 20u);
    expect_inside(pl, f.grid);
    EXPECT_EQ(pl.units, (Units{"mm", "s", "mm/s"}));  // 4DFlowNet: dx in mm, m/s converted
}
