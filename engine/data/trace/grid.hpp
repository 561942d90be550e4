// Regular grid of sample points (VTK "point data" convention: value k sits at
// origin + ijk * spacing) and the one trilinear sampler everything else uses.
#pragma once

#include <pathlet/scene.hpp>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace pathlet::trace {

struct Grid {
    glm::ivec3 dims{0};          // points per axis
    glm::vec3 origin{0.0f};      // world position of point (0,0,0)
    glm::vec3 spacing{1.0f};     // world distance between neighbouring points

    size_t count() const { return size_t(dims.x) * size_t(dims.y) * size_t(dims.z); }
    // x fastest, then y, then z (VTK order).
    size_t index(int i, int j, int k) const { return (size_t(k) * size_t(dims.y) + size_t(j)) * size_t(dims.x) + size_t(i); }
    size_t index(glm::ivec3 c) const { return index(c.x, c.y, c.z); }
    glm::ivec3 coord(size_t idx) const {
        const size_t sx = size_t(dims.x), sxy = sx * size_t(dims.y);
        return {int(idx % sx), int((idx / sx) % size_t(dims.y)), int(idx / sxy)};
    }
    glm::vec3 point(glm::ivec3 c) const { return origin + glm::vec3(c) * spacing; }
    glm::vec3 to_grid(glm::vec3 p) const { return (p - origin) / spacing; }
    bool in_range(glm::ivec3 c) const {
        return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < dims.x && c.y < dims.y && c.z < dims.z;
    }
    // Inside the box spanned by the first and last points (where trilinear is defined).
    bool contains(glm::vec3 p) const {
        const glm::vec3 g = to_grid(p);
        const glm::vec3 hi = glm::vec3(dims - 1);
        return g.x >= 0 && g.y >= 0 && g.z >= 0 && g.x <= hi.x && g.y <= hi.y && g.z <= hi.z;
    }
    // The grid point whose voxel (the cube of half-spacing around it) holds p.
    glm::ivec3 nearest(glm::vec3 p) const { return glm::ivec3(glm::floor(to_grid(p) + 0.5f)); }
    float min_spacing() const { return std::min({spacing.x, spacing.y, spacing.z}); }
    Bounds bounds() const { return {origin, origin + glm::vec3(dims - 1) * spacing}; }
};

// The 8 neighbours and weights of a position; clamped to the grid so samples just outside
// the box read the border (callers test `contains` where that matters).
struct TrilinearCell {
    size_t base = 0, dx = 0, dy = 0, dz = 0;  // index of the low corner and strides to its neighbours
    glm::vec3 f{0.0f};                         // fractional position inside the cell

    TrilinearCell(const Grid& g, glm::vec3 p) {
        glm::vec3 q = glm::clamp(g.to_grid(p), glm::vec3(0.0f), glm::vec3(g.dims - 1));
        glm::ivec3 c = glm::min(glm::ivec3(q), glm::max(g.dims - 2, glm::ivec3(0)));
        f = glm::clamp(q - glm::vec3(c), glm::vec3(0.0f), glm::vec3(1.0f));
        base = g.index(c);
        dx = g.dims.x > 1 ? 1 : 0;
        dy = g.dims.y > 1 ? size_t(g.dims.x) : 0;
        dz = g.dims.z > 1 ? size_t(g.dims.x) * size_t(g.dims.y) : 0;
    }

    template <class T>
    T sample(const T* v) const {
        const T* p = v + base;
        T x00 = p[0] + (p[dx] - p[0]) * f.x;
        T x10 = p[dy] + (p[dy + dx] - p[dy]) * f.x;
        T x01 = p[dz] + (p[dz + dx] - p[dz]) * f.x;
        T x11 = p[dz + dy] + (p[dz + dy + dx] - p[dz + dy]) * f.x;
        T y0 = x00 + (x10 - x00) * f.y;
        T y1 = x01 + (x11 - x01) * f.y;
        return y0 + (y1 - y0) * f.z;
    }
};

}  // namespace pathlet::trace
