#include "field_fixtures.hpp"

namespace pathlet::test {

trace::VelocityField make_field(glm::ivec3 dims, const std::function<glm::vec3(glm::vec3)>& fn, float spacing) {
    trace::VelocityField f;
    f.grid.dims = dims;
    f.grid.spacing = glm::vec3(spacing);
    f.frames.resize(1);
    f.frames[0].resize(f.grid.count());
    for (size_t i = 0; i < f.grid.count(); ++i) f.frames[0][i] = fn(f.grid.point(f.grid.coord(i)));
    f.frame_times = {0.0f};
    f.source = "analytic";
    return f;
}

std::vector<float> sphere_values(const trace::Grid& g, glm::vec3 centre, float radius) {
    std::vector<float> v(g.count());
    for (size_t i = 0; i < g.count(); ++i) v[i] = radius - glm::length(g.point(g.coord(i)) - centre);
    return v;
}

void mask_sphere(trace::VelocityField& f, glm::vec3 centre, float radius) {
    f.mask = sphere_values(f.grid, centre, radius);
    for (auto& m : f.mask) m = m >= 0.0f ? 1.0f : 0.0f;
}

}  // namespace pathlet::test
