#include "centerline.hpp"

#include <algorithm>
#include <cmath>

namespace pathlet::phantom {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kStep = 0.5f;  // mm between samples

// Position along the whole centreline for a parameter u in [0, 3): one unit per segment.
glm::vec3 curve(const ArchShape& a, float u) {
    if (u < 1.0f) return {0.0f, 0.0f, a.ascending_length * u};
    if (u < 2.0f) {
        const float th = kPi * (u - 1.0f);
        return {a.arch_lateral * (1.0f - std::cos(th)), -a.arch_radius * (1.0f - std::cos(th)),
                a.ascending_length + a.arch_radius * std::sin(th)};
    }
    const float v = (u - 2.0f) * a.descending_length;
    // A gentle S-bend so the descending aorta is not a perfect cylinder.
    return {2.0f * a.arch_lateral + 4.0f * std::sin(kPi * v / a.descending_length), -2.0f * a.arch_radius,
            a.ascending_length - v};
}

}  // namespace

float arch_end_s(const ArchShape& a) {
    // Arc length of the arch: integrate |curve'| numerically (it is nearly a half circle).
    float s = a.ascending_length;
    glm::vec3 prev = curve(a, 1.0f);
    for (int i = 1; i <= 2000; ++i) {
        const glm::vec3 p = curve(a, 1.0f + float(i) / 2000.0f);
        s += glm::length(p - prev);
        prev = p;
    }
    return s;
}

std::vector<CenterlineSample> make_centerline(const ArchShape& a) {
    // Dense parameter walk, keeping a sample every kStep of arc length.
    std::vector<CenterlineSample> out;
    const int fine = 60000;
    float s = 0.0f, next = 0.0f;
    glm::vec3 prev = curve(a, 0.0f);
    for (int i = 0; i <= fine; ++i) {
        const float u = 3.0f * float(i) / float(fine);
        const glm::vec3 p = curve(a, std::min(u, 2.99999f));
        s += glm::length(p - prev);
        prev = p;
        if (s + 1e-4f < next && i != fine) continue;
        CenterlineSample c;
        c.position = p;
        c.s = s;
        out.push_back(c);
        next = s + kStep;
    }
    const float s_arch0 = a.ascending_length, s_arch1 = arch_end_s(a), s_end = out.back().s;
    for (size_t i = 0; i < out.size(); ++i) {
        auto& c = out[i];
        const glm::vec3 d = out[std::min(i + 1, out.size() - 1)].position - out[i > 0 ? i - 1 : 0].position;
        c.tangent = glm::normalize(d);
        // Radius tapers root -> arch -> outlet.
        c.radius = c.s < s_arch1 ? a.radius_root + (a.radius_arch - a.radius_root) * smoothstep(0.0f, s_arch1, c.s)
                                 : a.radius_arch + (a.radius_outlet - a.radius_arch) * smoothstep(s_arch1, s_end, c.s);
        // Helical flow builds up through the arch and decays in the descending aorta.
        c.swirl = a.swirl * smoothstep(s_arch0 - 10.0f, s_arch0 + 20.0f, c.s) *
                  (1.0f - smoothstep(s_arch1 - 10.0f, s_arch1 + 60.0f, c.s));
    }
    return out;
}

}  // namespace pathlet::phantom
