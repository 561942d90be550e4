// Scene model helpers (declared in pathlet/scene.hpp).
#include <pathlet/scene.hpp>
#include <array>
#include <unordered_map>
#include <set>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathlet {

namespace {

bool finite3(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// Bounds over finite points; an empty set gives the invalid box lo > hi.
Bounds bounds_of(const std::vector<glm::vec3>& pts, Bounds b = {glm::vec3(INFINITY), glm::vec3(-INFINITY)}) {
    for (auto& p : pts)
        if (finite3(p)) {
            b.lo = glm::min(b.lo, p);
            b.hi = glm::max(b.hi, p);
        }
    return b;
}

}  // namespace

Bounds Pathlines::bounds() const { return bounds_of(position); }

float Pathlines::time_min() const {
    if (time.empty()) return 0.0f;
    float m = INFINITY;
    for (float t : time) if (std::isfinite(t)) m = std::min(m, t);
    return std::isfinite(m) ? m : 0.0f;
}

float Pathlines::time_max() const {
    if (time.empty()) return 0.0f;
    float m = -INFINITY;
    for (float t : time) if (std::isfinite(t)) m = std::max(m, t);
    return std::isfinite(m) ? m : 0.0f;
}

float Pathlines::speed_min() const {
    if (velocity.empty()) return 0.0f;
    float m = INFINITY;
    for (auto& v : velocity) if (finite3(v)) m = std::min(m, glm::length(v));
    return std::isfinite(m) ? m : 0.0f;
}

float Pathlines::speed_max() const {
    if (velocity.empty()) return 0.0f;
    float m = 0.0f;
    for (auto& v : velocity) if (finite3(v)) m = std::max(m, glm::length(v));
    return m;
}

const PointArray* Pathlines::array(const std::string& name) const {
    for (const PointArray& a : arrays)
        if (a.name == name) return &a;
    return nullptr;
}

void Pathlines::check_consistent(const std::string& what) const {
    const size_t n = position.size();
    if (time.size() != n)
        throw DataError(what + ": pathlines have " + std::to_string(n) + " positions but " + std::to_string(time.size()) + " times");
    if (velocity.size() != n)
        throw DataError(what + ": pathlines have " + std::to_string(n) + " positions but " + std::to_string(velocity.size()) +
                        " velocities");
    for (const PointArray& a : arrays)
        if (a.values.size() != n)
            throw DataError(what + ": point array '" + a.name + "' has " + std::to_string(a.values.size()) +
                            " values for " + std::to_string(n) + " points");
    for (size_t i = 0; i < lines.size(); ++i)
        if (uint64_t(lines[i].first) + lines[i].count > n)
            throw DataError(what + ": line " + std::to_string(i) + " (first " + std::to_string(lines[i].first) + ", count " +
                            std::to_string(lines[i].count) + ") runs past the " + std::to_string(n) + " points");
}

Bounds Mesh::bounds() const { return bounds_of(position); }

void Mesh::compute_normals() {
    normal.assign(position.size(), glm::vec3(0.0f));
    for (size_t i = 0; i + 2 < index.size(); i += 3) {
        uint32_t a = index[i], b = index[i + 1], c = index[i + 2];
        if (a >= position.size() || b >= position.size() || c >= position.size()) continue;
        // Cross product length is twice the area: area weighting for free.
        glm::vec3 n = glm::cross(position[b] - position[a], position[c] - position[a]);
        normal[a] += n;
        normal[b] += n;
        normal[c] += n;
    }
    for (auto& n : normal) {
        float l = glm::length(n);
        n = l > 0.0f && std::isfinite(l) ? n / l : glm::vec3(0.0f, 0.0f, 1.0f);
    }
}

Bounds Scene::bounds() const {
    Bounds b = lines.bounds();
    if (mesh) b = bounds_of(mesh->position, b);
    return b;
}

Mesh Mesh::simplified(float cell) const {
    if (!(cell > 0.0f) || empty()) return *this;
    const Bounds b = bounds();
    const bool have_normals = normal.size() == position.size();
    std::unordered_map<uint64_t, uint32_t> cluster_of_cell;
    std::vector<uint32_t> cluster(position.size());
    std::vector<glm::dvec3> sum_p, sum_n;
    std::vector<uint32_t> count;
    for (size_t v = 0; v < position.size(); ++v) {
        const glm::vec3 g = glm::floor((position[v] - b.lo) / cell);
        if (!(std::isfinite(g.x) && std::isfinite(g.y) && std::isfinite(g.z))) {
            cluster[v] = UINT32_MAX;  // a non-finite vertex: its triangles go
            continue;
        }
        const uint64_t key = (uint64_t(uint32_t(g.x) & 0x1FFFFF) << 42) | (uint64_t(uint32_t(g.y) & 0x1FFFFF) << 21) |
                             uint64_t(uint32_t(g.z) & 0x1FFFFF);
        auto [it, fresh] = cluster_of_cell.emplace(key, uint32_t(sum_p.size()));
        if (fresh) sum_p.emplace_back(0.0), sum_n.emplace_back(0.0), count.push_back(0);
        cluster[v] = it->second;
        sum_p[it->second] += glm::dvec3(position[v]);
        if (have_normals) sum_n[it->second] += glm::dvec3(normal[v]);
        ++count[it->second];
    }
    Mesh out;
    out.position.reserve(sum_p.size());
    for (size_t c = 0; c < sum_p.size(); ++c) out.position.push_back(glm::vec3(sum_p[c] / double(count[c])));
    std::set<std::array<uint32_t, 3>> seen;
    for (size_t t = 0; t + 2 < index.size(); t += 3) {
        std::array<uint32_t, 3> k{};
        bool ok = true;
        for (int j = 0; j < 3; ++j) {
            const uint32_t v = index[t + size_t(j)];
            ok = ok && v < cluster.size() && cluster[v] != UINT32_MAX;
            k[size_t(j)] = ok ? cluster[v] : 0;
        }
        if (!ok || k[0] == k[1] || k[1] == k[2] || k[0] == k[2]) continue;  // collapsed
        std::array<uint32_t, 3> canon = k;  // the same triangle in any rotation, same winding
        std::rotate(canon.begin(), std::min_element(canon.begin(), canon.end()), canon.end());
        if (!seen.insert(canon).second) continue;
        out.index.insert(out.index.end(), k.begin(), k.end());
    }
    if (have_normals) {
        out.normal.reserve(sum_n.size());
        for (const auto& n : sum_n) out.normal.push_back(glm::length(n) > 0.0 ? glm::vec3(glm::normalize(n)) : glm::vec3(0, 0, 1));
    } else {
        out.compute_normals();
    }
    return out;
}

}  // namespace pathlet
