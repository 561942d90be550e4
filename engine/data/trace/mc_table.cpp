// Generates the marching-cubes case table instead of carrying 256x16 literals.
//
// For each configuration, every cube face contributes segments between its crossed edges:
// walking the face's corners counter-clockwise (seen from outside), an edge entering the
// inside is joined to the next edge leaving it. On an ambiguous face this separates the two
// inside corners; the rule depends only on the face's four corners, so the two cubes sharing
// a face always agree and the surface is closed. Each crossed edge is entered on one of its
// faces and left on the other, so the segments chain into loops; each loop is fanned into
// triangles from a vertex whose diagonals never lie on a cube face (a neighbour cube could
// use the same diagonal, giving an edge shared by four triangles). Orientation is fixed
// once against the one-corner case.
#include "marching_cubes.hpp"

#include <glm/glm.hpp>

#include <algorithm>

namespace pathlet::trace {
namespace {

constexpr std::array<std::array<uint8_t, 2>, 12> kEdges{{
    {0, 1}, {2, 3}, {4, 5}, {6, 7},  // along x
    {0, 2}, {1, 3}, {4, 6}, {5, 7},  // along y
    {0, 4}, {1, 5}, {2, 6}, {3, 7},  // along z
}};

// Corners of each face, counter-clockwise seen from outside the cube.
constexpr std::array<std::array<uint8_t, 4>, 6> kFaces{{
    {0, 4, 6, 2}, {1, 3, 7, 5},  // x = 0, x = 1
    {0, 1, 5, 4}, {2, 6, 7, 3},  // y = 0, y = 1
    {0, 2, 3, 1}, {4, 5, 7, 6},  // z = 0, z = 1
}};

int edge_between(int a, int b) {
    for (int e = 0; e < 12; ++e)
        if ((kEdges[e][0] == a && kEdges[e][1] == b) || (kEdges[e][0] == b && kEdges[e][1] == a)) return e;
    return -1;
}

bool share_face(int e1, int e2) {
    for (const auto& f : kFaces) {
        int hits = 0;
        for (int k = 0; k < 4; ++k) {
            const int e = edge_between(f[k], f[(k + 1) % 4]);
            hits += (e == e1) + (e == e2);
        }
        if (hits == 2) return true;
    }
    return false;
}

// First rotation of the loop whose fan diagonals all cross the cube's interior.
size_t fan_start(const std::vector<uint8_t>& loop) {
    const size_t n = loop.size();
    for (size_t r = 0; r < n; ++r) {
        bool ok = true;
        for (size_t i = 2; i + 1 < n && ok; ++i) ok = !share_face(loop[r], loop[(r + i) % n]);
        if (ok) return r;
    }
    return 0;
}

McCase build_case(int config, bool flip) {
    auto in = [&](int corner) { return (config >> corner) & 1; };
    std::array<int, 12> next;
    next.fill(-1);
    for (const auto& f : kFaces) {
        for (int k = 0; k < 4; ++k) {
            if (in(f[k]) || !in(f[(k + 1) % 4])) continue;  // not an entering edge
            for (int m = 1; m <= 4; ++m) {
                const int a = f[(k + m) % 4], b = f[(k + m + 1) % 4];
                if (in(a) && !in(b)) {
                    next[edge_between(f[k], f[(k + 1) % 4])] = edge_between(a, b);
                    break;
                }
            }
        }
    }
    McCase out;
    std::array<bool, 12> used{};
    for (int start = 0; start < 12; ++start) {
        if (next[start] < 0 || used[start]) continue;
        std::vector<uint8_t> loop;
        for (int e = start; !used[e]; e = next[e]) {
            used[e] = true;
            loop.push_back(uint8_t(e));
        }
        std::rotate(loop.begin(), loop.begin() + std::ptrdiff_t(fan_start(loop)), loop.end());
        for (size_t i = 1; i + 1 < loop.size(); ++i) {
            if (flip) out.tris.push_back({loop[0], loop[i + 1], loop[i]});
            else out.tris.push_back({loop[0], loop[i], loop[i + 1]});
        }
    }
    return out;
}

glm::vec3 corner_pos(int c) { return glm::vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1); }
glm::vec3 edge_mid(int e) { return 0.5f * (corner_pos(kEdges[e][0]) + corner_pos(kEdges[e][1])); }

std::array<McCase, 256> build_table() {
    // Only corner 0 inside: the normal must point away from it, i.e. along +(1,1,1).
    const McCase probe = build_case(1, false);
    const auto& t = probe.tris.at(0);
    const glm::vec3 n = glm::cross(edge_mid(t[1]) - edge_mid(t[0]), edge_mid(t[2]) - edge_mid(t[0]));
    const bool flip = glm::dot(n, glm::vec3(1.0f)) < 0.0f;
    std::array<McCase, 256> table;
    for (int c = 0; c < 256; ++c) table[c] = build_case(c, flip);
    return table;
}

}  // namespace

const std::array<McCase, 256>& mc_table() {
    static const std::array<McCase, 256> table = build_table();
    return table;
}

const std::array<std::array<uint8_t, 2>, 12>& mc_edges() { return kEdges; }

}  // namespace pathlet::trace
