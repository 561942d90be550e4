// describe_file(): the text behind `pathlet info FILE`.
#include "io/file_info.hpp"
#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
#include "io/tract_formats.hpp"
#include "io_test_util.hpp"

using namespace pathlet;
using namespace pathlet::io;

namespace {

TEST(IoInfo, PathlinesSummary) {
    Pathlines p = iotest::make_lines(5, 10);
    std::string path = iotest::temp_dir() + "/a.vtp";
    save_pathlines(p, path, PathlineFormat::VtpZlib);
    std::string s = describe_file(path);
    for (const char* needle : {"format:    VTK XML PolyData", "lines:     5", "points:    60", "time (1 comp), velocity (3 comp)",
                               "time:      ", "speed:     ", "bounds:    x ", "points per line: min 10, median 12, max 14",
                               "warnings:  none"})
        EXPECT_NE(s.find(needle), std::string::npos) << needle << "\n" << s;
}

TEST(IoInfo, UnitsWhereKnownAndTractsWithoutTime) {
    Pathlines p = iotest::make_lines(3, 8);
    const std::string dir = iotest::temp_dir();
    save_pathlines(p, dir + "/none.vtp", PathlineFormat::VtpZlib);
    std::string s = describe_file(dir + "/none.vtp");
    EXPECT_NE(s.find("units:     not given (the file does not say them all: --units LENGTH[,VELOCITY])"), std::string::npos) << s;
    EXPECT_EQ(s.find(" mm"), std::string::npos) << s;
    p.units = {"mm", "s", "mm/s"};
    save_pathlines(p, dir + "/mm.vtp", PathlineFormat::VtpZlib);
    s = describe_file(dir + "/mm.vtp");
    for (const char* needle : {"units:     length mm, time s, velocity mm/s\n", " s (span ", " mm/s\n", " (mm)\n"})
        EXPECT_NE(s.find(needle), std::string::npos) << needle << "\n" << s;
    // --units over a file that says nothing; the velocity's "per s" names the time's unit.
    LoadOptions o;
    o.units = "m,m/s";
    s = describe_file(dir + "/none.vtp", o);
    EXPECT_NE(s.find("units:     length m, time s, velocity m/s\n"), std::string::npos) << s;
    // Tracts: mm, no time, no speed.
    iotest::write_bytes(dir + "/t.tck", write_tck(p));
    s = describe_file(dir + "/t.tck");
    for (const char* needle : {"format:    MRtrix .tck, Float32LE", "units:     length mm\n", "time:      none (streamlines"})
        EXPECT_NE(s.find(needle), std::string::npos) << needle << "\n" << s;
    EXPECT_EQ(s.find("speed:"), std::string::npos) << s;
}

TEST(IoInfo, MeshSummaryAndErrors) {
    Mesh m;
    m.position = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.index = {0, 1, 2};
    std::string dir = iotest::temp_dir();
    save_mesh(m, dir + "/m.glb");
    std::string s = describe_file(dir + "/m.glb");
    EXPECT_NE(s.find("vertices:  3"), std::string::npos) << s;
    EXPECT_NE(s.find("triangles: 1"), std::string::npos) << s;
    EXPECT_THROW(describe_file(dir + "/missing.vtk"), DataError);
}

}  // namespace
