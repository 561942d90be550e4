// Marching cubes over a grid of values: the surface where value == iso, "inside" being
// value >= iso. Triangles wind counter-clockwise seen from outside (normals point away
// from the inside). Vertices on shared cube edges are merged, so a surface that stays
// inside the grid is closed. Normals are area-weighted face normals.
#pragma once

#include "grid.hpp"
#include "progress.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace pathlet::trace {

Mesh marching_cubes(const Grid& grid, const std::vector<float>& values, float iso, const Progress& progress = {});

// The 256-case table, generated (not typed in): for each corner configuration, triangles
// as triples of cube edge ids. Corner c sits at (c & 1, c >> 1 & 1, c >> 2 & 1); edge ids
// are listed in mc_table.cpp. Exposed for tests.
struct McCase {
    std::vector<std::array<uint8_t, 3>> tris;
};
const std::array<McCase, 256>& mc_table();
// Corner pair of each of the 12 edges.
const std::array<std::array<uint8_t, 2>, 12>& mc_edges();

}  // namespace pathlet::trace
