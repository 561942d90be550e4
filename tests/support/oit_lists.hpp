#pragma once
// Variant 2's per-pixel lists as the GPU left them (`heads` and `nodes` of a graph with
// fill_list), read in a render's frame callback: the one reading the OIT tests compare their CPU
// versions of a technique against.
#include "executor.hpp"

#include <glm/glm.hpp>

#include <vector>

namespace pathlet {

struct OitLists {
    int width = 0, height = 0;
    std::vector<GLuint> heads;      // GL rows (bottom-up); 0xFFFFFFFF ends a list
    std::vector<glm::uvec4> nodes;  // x: RGBA8 colour, y: float depth bits, z: next, w: line id
    // A pixel's list head, (x, y) in GL rows.
    GLuint head(int x, int y) const { return heads[size_t(y) * size_t(width) + size_t(x)]; }
};

// Reads the executor's resources `heads` and `nodes` (synchronously: a test asks for them).
OitLists read_oit_lists(const Executor& ex);

// A node's colour, RGBA8 unpacked to [0, 1].
glm::dvec4 node_color(GLuint packed);
// A node's depth (the float stored in y).
double node_depth(const glm::uvec4& node);

}  // namespace pathlet
