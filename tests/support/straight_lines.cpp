#include "straight_lines.hpp"

#include <fstream>

namespace pathlet {

Scene straight_lines_scene(const std::vector<StraightLine>& lines, const std::vector<std::string>& array_names) {
    Scene s;
    Pathlines& pl = s.lines;
    for (const std::string& n : array_names) pl.arrays.push_back({n, {}});
    for (const StraightLine& l : lines) {
        const glm::vec3 d = l.to - l.from;
        const float len = glm::length(d);
        pl.lines.push_back({uint32_t(pl.position.size()), uint32_t(l.points)});
        for (int k = 0; k < l.points; ++k) {
            const float f = float(k) / float(l.points - 1);
            pl.position.push_back(l.from + f * d);
            pl.velocity.push_back(d / len * l.speed);
            pl.time.push_back(f * len / l.speed);
            for (size_t a = 0; a < array_names.size(); ++a) pl.arrays[a].values.push_back(l.arrays.at(a));
        }
    }
    pl.units = {"mm", "s", "mm/s"};
    s.source = "straight lines (tests/support)";
    return s;
}

std::string write_camera_down_z(const std::string& path, glm::vec3 t, float distance, float fov_deg) {
    std::ofstream(path) << "{\"keyframes\": [{\"time\": 0, \"eye\": [" << t.x << ", " << t.y << ", " << t.z + distance
                        << "], \"target\": [" << t.x << ", " << t.y << ", " << t.z << "], \"up\": [0, 1, 0], \"fov\": "
                        << fov_deg << "}]}";
    return path;
}

}  // namespace pathlet
