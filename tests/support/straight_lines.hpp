// Scenes of straight pathlines for tests where the answer is known: each line runs from `from`
// to `to` at a constant speed (time = arc length / speed from 0), with optional point arrays
// holding one constant per line.
#pragma once

#include <pathlet/scene.hpp>

#include <string>
#include <vector>

namespace pathlet {

struct StraightLine {
    glm::vec3 from{0.0f}, to{1.0f, 0.0f, 0.0f};
    float speed = 1.0f;
    int points = 101;
    std::vector<float> arrays{};  // one value per array name of straight_lines_scene, constant along the line
};

// Units mm, s, mm/s. `array_names` name the values of StraightLine::arrays.
Scene straight_lines_scene(const std::vector<StraightLine>& lines, const std::vector<std::string>& array_names = {});

// Writes a camera path looking down -z at `target` from `distance` with fovy `fov_deg`, +y up.
std::string write_camera_down_z(const std::string& path, glm::vec3 target, float distance, float fov_deg);

}  // namespace pathlet
