// Scene model helpers (declared in pathlet/scene.hpp).
#include <pathlet/scene.hpp>

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

void Pathlines::check_consistent(const std::string& what) const {
    const size_t n = position.size();
    if (time.size() != n)
        throw DataError(what + ": pathlines have " + std::to_string(n) + " positions but " + std::to_string(time.size()) + " times");
    if (velocity.size() != n)
        throw DataError(what + ": pathlines have " + std::to_string(n) + " positions but " + std::to_string(velocity.size()) +
                        " velocities");
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

}  // namespace pathlet
