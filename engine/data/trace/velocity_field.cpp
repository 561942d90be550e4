#include "velocity_field.hpp"

#include <cmath>

namespace pathlet::trace {

float VelocityField::cycle() const {
    if (frame_times.size() < 2) return 0.0f;
    const float span = frame_times.back() - frame_times.front();
    return span + span / float(frame_times.size() - 1);
}

size_t VelocityField::vessel_voxels() const {
    size_t n = 0;
    for (size_t i = 0; i < grid.count(); ++i) n += inside_voxel(i) ? 1 : 0;
    return n;
}

float VelocityField::max_speed() const {
    float m = 0.0f;
    for (const auto& f : frames)
        for (size_t i = 0; i < f.size(); ++i)
            if (inside_voxel(i)) m = std::max(m, glm::length(f[i]));
    return m;
}

void VelocityField::mask_from_scalars(float threshold) {
    if (scalars.empty()) throw DataError(source + ": no scalar volume to threshold for a mask");
    mask.assign(scalars.size(), 0.0f);
    for (size_t i = 0; i < scalars.size(); ++i) mask[i] = scalars[i] > threshold ? 1.0f : 0.0f;
}

void VelocityField::check(size_t* nonfinite_fixed) {
    const size_t n = grid.count();
    if (n == 0 || glm::any(glm::lessThan(grid.dims, glm::ivec3(1))))
        throw DataError(source + ": empty grid");
    if (!(glm::all(glm::greaterThan(grid.spacing, glm::vec3(0.0f)))) || !std::isfinite(grid.spacing.x + grid.spacing.y + grid.spacing.z))
        throw DataError(source + ": spacing must be positive and finite");
    if (frames.empty()) throw DataError(source + ": no velocity data");
    if (frame_times.size() != frames.size()) throw DataError(source + ": frame times do not match frames");
    for (size_t f = 0; f < frames.size(); ++f) {
        if (frames[f].size() != n) throw DataError(source + ": frame " + std::to_string(f) + " has wrong size");
        if (f > 0 && !(frame_times[f] > frame_times[f - 1])) throw DataError(source + ": frame times must ascend");
    }
    if (!mask.empty() && mask.size() != n) throw DataError(source + ": mask has wrong size");
    if (!scalars.empty() && scalars.size() != n) throw DataError(source + ": scalars have wrong size");
    size_t fixed = 0;
    for (auto& f : frames)
        for (auto& v : f)
            if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) v = glm::vec3(0.0f), ++fixed;
    for (auto& m : mask)
        if (!std::isfinite(m)) m = 0.0f, ++fixed;
    if (nonfinite_fixed) *nonfinite_fixed = fixed;
}

}  // namespace pathlet::trace
