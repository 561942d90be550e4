#include "marching_cubes.hpp"

#include "velocity_field.hpp"

#include <pathlet/scene.hpp>

#include <algorithm>
#include <numeric>
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

Mesh drop_small_pieces(const Mesh& m, float min_share, PieceStats* stats) {
    // Union-find over vertices; a triangle joins its three.
    std::vector<uint32_t> parent(m.position.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (size_t t = 0; t + 2 < m.index.size(); t += 3) {
        const uint32_t a = find(m.index[t]);
        for (int k = 1; k < 3; ++k) {
            const uint32_t b = find(m.index[t + size_t(k)]);
            if (a != b) parent[b] = a;
        }
    }
    std::unordered_map<uint32_t, size_t> triangles;  // root -> triangle count
    for (size_t t = 0; t + 2 < m.index.size(); t += 3) ++triangles[find(m.index[t])];
    size_t largest = 0;
    for (auto& [root, n] : triangles) largest = std::max(largest, n);
    const double keep_from = double(min_share) * double(largest);
    Mesh out;
    std::vector<uint32_t> remap(m.position.size(), UINT32_MAX);
    PieceStats st;
    st.pieces = triangles.size();
    for (auto& [root, n] : triangles) st.kept += double(n) >= keep_from;
    for (size_t t = 0; t + 2 < m.index.size(); t += 3) {
        if (double(triangles[find(m.index[t])]) < keep_from) {
            ++st.dropped_triangles;
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = m.index[t + size_t(k)];
            if (remap[v] == UINT32_MAX) {
                remap[v] = uint32_t(out.position.size());
                out.position.push_back(m.position[v]);
                if (m.normal.size() == m.position.size()) out.normal.push_back(m.normal[v]);
            }
            out.index.push_back(remap[v]);
        }
    }
    if (stats) *stats = st;
    return out;
}

Mesh vessel_wall(const VelocityField& field, float min_piece_share, PieceStats* stats, const Progress& progress) {
    if (field.mask.empty()) throw DataError(field.source + ": no mask (or --mask-threshold), so no wall to extract");
    return drop_small_pieces(marching_cubes(field.grid, field.mask, 0.5f, progress), min_piece_share, stats);
}

}  // namespace pathlet::trace
