// Per-line post-processing of traced pathlines: 1-D binomial smoothing, arc-length
// resampling, length; and the voxel hash used to find lines too close to accepted ones.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace pathlet::trace {

// One pathline being built: samples ordered by ascending time.
struct TracedLine {
    std::vector<glm::vec3> position;
    std::vector<float> time;
    std::vector<glm::vec3> velocity;
    size_t size() const { return position.size(); }
};

float polyline_length(const std::vector<glm::vec3>& p);

// `passes` times the [1 2 1]/4 kernel over the interior points; the two endpoints stay put.
void binomial_smooth(std::vector<glm::vec3>& p, int passes);

// Resamples to points `step` apart along the polyline (the last point is always kept;
// time and velocity are interpolated linearly in arc length).
TracedLine resample_by_length(const TracedLine& in, float step);

// Points of accepted lines bucketed by cells of size `radius`; answers "is any stored point
// within radius of p" by looking at the 27 cells around p.
class ProximityHash {
public:
    explicit ProximityHash(float radius) : r_(radius), inv_(radius > 0 ? 1.0f / radius : 0.0f) {}
    void insert(glm::vec3 p);
    void merge(const ProximityHash& other);  // inserts all of other's points
    void clear();
    bool near(glm::vec3 p) const;
    // Fraction of points of `pts` that are near a stored point.
    float near_fraction(const std::vector<glm::vec3>& pts) const;

private:
    static uint64_t key(glm::ivec3 c);
    glm::ivec3 cell(glm::vec3 p) const { return glm::ivec3(glm::floor(p * inv_)); }
    // Open-addressing table cell key -> first point (points of a cell are linked through
    // next_); std::unordered_map's modulo and node chasing made this the tracer's hot spot.
    uint32_t* slot(uint64_t key);
    uint32_t find(uint64_t key) const;
    void grow();
    float r_, inv_;
    std::vector<uint64_t> keys_;
    std::vector<uint32_t> heads_;
    size_t used_ = 0;
    std::vector<glm::vec3> pts_;
    std::vector<uint32_t> next_;
};

}  // namespace pathlet::trace
