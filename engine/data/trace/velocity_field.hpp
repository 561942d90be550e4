// A velocity volume: a regular grid, one or more time frames of vec3 velocity per grid
// point, and optionally a mask (inside >= 0.5) or a scalar volume to threshold into one.
// Positions are world units (what the file says, usually mm); velocity is world units/s.
#pragma once

#include "grid.hpp"

#include <string>
#include <vector>

namespace pathlet::trace {

struct VelocityField {
    Grid grid;
    std::vector<std::vector<glm::vec3>> frames;  // each grid.count() long
    std::vector<float> frame_times;              // seconds, ascending, one per frame
    std::vector<float> mask;                     // empty: everything inside the grid is vessel
    std::vector<float> scalars;                  // optional intensity volume (VTK SCALARS)
    std::string scalars_name;
    std::string source;                          // file it came from, for messages
    // Length and velocity units where the source says them (Units::time is unused here: the
    // tracer's clock is seconds of the velocity's time base); "" = not known.
    Units units;

    bool steady() const { return frames.size() <= 1; }
    // Length of one cycle when the frames are taken as periodic: last - first + one frame step.
    float cycle() const;
    bool inside_voxel(size_t idx) const { return mask.empty() || mask[idx] >= 0.5f; }
    size_t vessel_voxels() const;
    float max_speed() const;  // over vessel voxels of all frames

    // mask = 1 where scalars > threshold, else 0. Throws DataError if there are no scalars.
    void mask_from_scalars(float threshold);
    // Sizes agree, times ascend, values finite (non-finite velocity becomes 0, counted).
    // Throws DataError naming `source`.
    void check(size_t* nonfinite_fixed = nullptr);
};

}  // namespace pathlet::trace
