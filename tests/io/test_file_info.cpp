// describe_file(): the text behind `pathlet info FILE`.
#include "io/file_info.hpp"
#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
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
