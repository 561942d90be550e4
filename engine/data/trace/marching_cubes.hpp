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

// The mesh without its small pieces: a piece (triangles connected through shared vertices)
// with fewer than `min_share` of the largest piece's triangles is dropped, and so are the
// vertices only it used. A thresholded scan's noise specks go, vessel branches stay.
struct PieceStats {
    size_t pieces = 0, kept = 0, dropped_triangles = 0;
};
Mesh drop_small_pieces(const Mesh& m, float min_share, PieceStats* stats = nullptr);

// The vessel wall of a velocity volume, as `pathlet trace --wall` writes it: marching cubes
// of the mask at 0.5 without pieces under `min_piece_share` of the largest (default 1 %).
// Needs a mask (DataError naming the field otherwise).
struct VelocityField;
Mesh vessel_wall(const VelocityField& field, float min_piece_share = 0.01f, PieceStats* stats = nullptr,
                 const Progress& progress = {});

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
