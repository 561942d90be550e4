// Cameras: a default that frames the data, keyframed camera paths from JSON, and a
// turntable orbit. All produce a pathlet::Camera for a given time and output size.
#pragma once

#include <pathlet/pass.hpp>
#include <pathlet/scene.hpp>

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace pathlet {

// Looks along the bounding box's thinnest axis (so an aortic arch is seen side on), with the
// longest remaining axis up; near/far hug the bounding sphere so linear depth uses [0,1] well.
Camera frame_bounds(const Bounds& b, glm::ivec2 size, float fov_y_deg = 40.0f);

// The points whose projection frames a figure: the lines' and the wall's, at most max_points
// (an even subsample that keeps the points on the bounding box's faces).
std::vector<glm::vec3> framing_points(const Scene& scene, size_t max_points = 0);

// The render command's default camera: frame_bounds, moved in where the data (its points)
// would fill less than 80 % of the frame's limiting dimension, until it fills 92 %
// (a compact data set whose bounding sphere is much larger than what it shows).
Camera frame_points(const Bounds& b, const std::vector<glm::vec3>& points, glm::ivec2 size, float fov_y_deg = 40.0f);

// frame_bounds' view at the distance where the points (the box's corners when there are none)
// fill `fill` of the limiting dimension at the widest angle of an orbit about the up axis: for
// render --orbit, whose every frame must show all of the data.
Camera frame_bounds_orbit(const Bounds& b, const std::vector<glm::vec3>& points, glm::ivec2 size,
                          float fov_y_deg = 40.0f, float fill = 0.95f);

// Recomputes view/proj from eye/target/up/fov, with near/far fitted to the bounds.
void finish_camera(Camera& c, const Bounds& b, glm::ivec2 size);

// Rotates the eye about the target around the up axis by deg_per_s * t.
Camera orbit(const Camera& base, double deg_per_s, double t, const Bounds& b, glm::ivec2 size);

// {"keyframes": [{"time": 0, "eye": [x,y,z], "target": [x,y,z], "up": [0,0,1], "fov": 40}, ...]}
// Interpolated with Catmull-Rom in position, linearly in fov; clamped outside the key range.
class CameraPath {
public:
    static CameraPath load(const std::string& path);  // DataError naming file and JSON pointer
    static CameraPath parse(const std::string& json_text, const std::string& path_for_messages);
    Camera at(double t, const Bounds& b, glm::ivec2 size) const;
    size_t size() const { return keys_.size(); }

private:
    struct Key {
        double time;
        glm::vec3 eye, target, up;
        float fov;
    };
    std::vector<Key> keys_;
};

}  // namespace pathlet
