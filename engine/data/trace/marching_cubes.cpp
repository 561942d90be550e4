#include "marching_cubes.hpp"

#include <pathlet/scene.hpp>

#include <algorithm>
#include <unordered_map>

namespace pathlet::trace {

Mesh marching_cubes(const Grid& g, const std::vector<float>& values, float iso, const Progress& progress) {
    Mesh mesh;
    if (values.size() != g.count()) throw DataError("marching cubes: value count does not match the grid");
    if (glm::any(glm::lessThan(g.dims, glm::ivec3(2)))) return mesh;
    const auto& table = mc_table();
    const auto& edges = mc_edges();
    auto corner = [](int c) { return glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1); };

    std::unordered_map<uint64_t, uint32_t> vertex_of_edge;  // grid edge -> vertex (shared by 4 cells)
    auto vertex = [&](glm::ivec3 cell, int e) {
        const glm::ivec3 a = cell + corner(edges[e][0]), b = cell + corner(edges[e][1]);
        const size_t ia = g.index(a), ib = g.index(b);
        const uint64_t key = uint64_t(ia) * 3 + uint64_t(e / 4);  // low corner + axis
        auto [it, fresh] = vertex_of_edge.try_emplace(key, uint32_t(mesh.position.size()));
        if (fresh) {
            const float va = values[ia], vb = values[ib];
            const float t = vb != va ? std::clamp((iso - va) / (vb - va), 0.0f, 1.0f) : 0.5f;
            mesh.position.push_back(g.point(a) + (g.point(b) - g.point(a)) * t);
        }
        return it->second;
    };

    for (int k = 0; k + 1 < g.dims.z; ++k) {
        for (int j = 0; j + 1 < g.dims.y; ++j)
            for (int i = 0; i + 1 < g.dims.x; ++i) {
                const glm::ivec3 cell(i, j, k);
                int config = 0;
                for (int c = 0; c < 8; ++c)
                    if (values[g.index(cell + corner(c))] >= iso) config |= 1 << c;
                for (const auto& t : table[config].tris)
                    for (uint8_t e : t) mesh.index.push_back(vertex(cell, e));
            }
        if ((k & 15) == 0) report(progress, double(k) / double(g.dims.z - 1), "marching cubes");
    }

    // Area-weighted face normals (the cross product's length is twice the area).
    mesh.normal.assign(mesh.position.size(), glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < mesh.index.size(); t += 3) {
        const uint32_t a = mesh.index[t], b = mesh.index[t + 1], c = mesh.index[t + 2];
        const glm::vec3 n = glm::cross(mesh.position[b] - mesh.position[a], mesh.position[c] - mesh.position[a]);
        mesh.normal[a] += n, mesh.normal[b] += n, mesh.normal[c] += n;
    }
    for (auto& n : mesh.normal) {
        const float l = glm::length(n);
        n = l > 0.0f ? n / l : glm::vec3(0.0f, 0.0f, 1.0f);
    }
    report(progress, 1.0, "marching cubes");
    return mesh;
}

}  // namespace pathlet::trace
