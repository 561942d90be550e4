// Centreline of the synthetic aortic arch (world units mm): ascending aorta straight up
// (+z) from the root, an arch bending back (-y) and to the left (+x), and the descending
// aorta going down. Sampled every ~0.5 mm with tangent, lumen radius and swirl strength.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <vector>

namespace pathlet::phantom {

struct CenterlineSample {
    glm::vec3 position{0.0f};
    glm::vec3 tangent{0.0f, 0.0f, 1.0f};  // unit, downstream
    float s = 0.0f;                       // arc length from the root, mm
    float radius = 0.0f;                  // lumen radius, mm
    float swirl = 0.0f;                   // helical secondary flow, fraction of the mean speed
};

struct ArchShape {
    float ascending_length = 50.0f;   // mm
    float arch_radius = 30.0f;        // mm, radius of the bend
    float arch_lateral = 8.0f;        // mm, leftward shift over the arch (makes it non-planar)
    float descending_length = 150.0f; // mm
    float radius_root = 14.0f, radius_arch = 13.0f, radius_outlet = 11.0f;  // mm
    float swirl = 0.35f;              // peak helical strength in the arch
};

std::vector<CenterlineSample> make_centerline(const ArchShape& shape);

// Arc length where the arch ends and the descending aorta starts.
float arch_end_s(const ArchShape& shape);

// 0 below a, 1 above b, a smooth cubic between (GLSL's smoothstep): the phantom's blends.
inline float smoothstep(float a, float b, float x) {
    const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

}  // namespace pathlet::phantom
