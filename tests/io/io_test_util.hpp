// Helpers shared by the io tests: synthetic pathlines, a per-test temp dir, byte I/O.
#pragma once

#include "io/pathline_io.hpp"

#include <pathlet/scene.hpp>

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace iotest {

// `lines` pathlines with `per_line` points each (varying by line), strictly increasing
// time, smooth positions and velocities; values are not "nice" so ASCII precision matters.
pathlet::Pathlines make_lines(size_t lines, size_t per_line, uint32_t seed = 1);

// A fresh directory under the build tree for this test.
std::string temp_dir();
std::string read_bytes(const std::string& path);
void write_bytes(const std::string& path, const std::string& bytes);

// Exact comparison (bitwise float equality) of everything.
void expect_same(const pathlet::Pathlines& a, const pathlet::Pathlines& b);

// Directory with the shared real data, or "" when absent.
std::string real_data_dir();

// A test with a fresh directory: put(name, bytes) writes a file there and returns its path.
struct FileTest : ::testing::Test {
    std::string dir = temp_dir();
    std::string put(const std::string& name, const std::string& bytes) const {
        const std::string p = dir + "/" + name;
        write_bytes(p, bytes);
        return p;
    }
};

// The bytes every pathline writer makes of `p`, named by format: VTK legacy ASCII, BINARY and
// 5.1 (a/b/c.vtk), VTP in every encoding with and without zlib (vEZ.vtp), the native cache.
std::vector<std::pair<std::string, std::string>> every_writer(const pathlet::Pathlines& p);

// Whether one of the report's warnings (or array descriptions) contains `needle`.
bool reports(const pathlet::io::LoadReport& r, const std::string& needle);

}  // namespace iotest
