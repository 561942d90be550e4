// Helpers shared by the io tests: synthetic pathlines, a per-test temp dir, byte I/O.
#pragma once

#include <pathlet/scene.hpp>

#include <gtest/gtest.h>

#include <string>

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

}  // namespace iotest
