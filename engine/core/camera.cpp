#include "camera.hpp"

#include "util/input_limits.hpp"
#include "util/text.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace pathlet {

void finish_camera(Camera& c, const Bounds& b, glm::ivec2 size) {
    // Relative to the data only (a degenerate box, one point, falls back to 1): no floor in
    // world units, so a scene framed at any scale gets the same picture.
    float r = b.valid() && b.radius() > 0.0f ? b.radius() : 1.0f;
    float d = glm::length(c.eye - (b.valid() ? b.center() : c.target));
    c.near_plane = std::max(d - 1.05f * r, 0.01f * r);
    c.far_plane = d + 1.05f * r;
    c.view = glm::lookAt(c.eye, c.target, c.up);
    float aspect = size.y > 0 ? float(size.x) / float(size.y) : 1.0f;
    c.proj = glm::perspective(glm::radians(c.fov_y_deg), aspect, c.near_plane, c.far_plane);
}

namespace {
// The distance from the box's centre at which its 8 corners, seen along `v` with `up` up, fill
// `fill` of the frame's limiting dimension. A corner q (from the centre) lies at depth d + q.v
// with offsets q.right, q.up: it fits when d >= |offset| / (tan * fill) - q.v.
float fit_distance(const std::vector<glm::vec3>& points, glm::vec3 center, glm::vec3 v, glm::vec3 up, float tan_v,
                   float aspect, float fill) {
    const glm::vec3 right = glm::normalize(glm::cross(v, up)), cam_up = glm::cross(right, v);
    const float tv = tan_v * fill, th = tv * aspect;
    float dist = 0.0f;
    for (const glm::vec3& p : points) {
        const glm::vec3 q = p - center;
        const float depth = glm::dot(q, v);
        dist = std::max({dist, std::fabs(glm::dot(q, right)) / th - depth, std::fabs(glm::dot(q, cam_up)) / tv - depth});
    }
    return dist;
}

std::vector<glm::vec3> corners(const Bounds& b) {
    std::vector<glm::vec3> c;
    for (int i = 0; i < 8; ++i) c.emplace_back(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
    return c;
}
}  // namespace

std::vector<glm::vec3> framing_points(const Scene& scene, size_t max_points) {
    std::vector<glm::vec3> all;
    auto add = [&](const std::vector<glm::vec3>& v) {
        for (const glm::vec3& p : v)
            if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) all.push_back(p);
    };
    add(scene.lines.position);
    if (scene.mesh) add(scene.mesh->position);
    if (all.size() <= max_points || max_points == 0) return all;
    std::vector<glm::vec3> some;  // an even subsample, with the box's extremes kept exactly
    const Bounds b = scene.bounds();
    const size_t step = (all.size() + max_points - 1) / max_points;
    for (size_t i = 0; i < all.size(); ++i)
        if (i % step == 0 || glm::any(glm::equal(all[i], b.lo)) || glm::any(glm::equal(all[i], b.hi))) some.push_back(all[i]);
    return some;
}

Camera frame_points(const Bounds& b, const std::vector<glm::vec3>& points, glm::ivec2 size, float fov_y_deg) {
    Camera c = frame_bounds(b, size, fov_y_deg);
    if (points.empty() || !b.valid()) return c;
    const glm::vec3 v = glm::normalize(c.target - c.eye);
    const float aspect = size.y > 0 ? float(size.x) / float(size.y) : 1.0f, tan_v = std::tan(glm::radians(fov_y_deg) * 0.5f);
    // The sphere leaves a compact data set (in a box near a cube) small in the frame: where the
    // data would fill less than 80 % of the limiting dimension, move in until it fills 92 %.
    if (glm::length(c.eye - c.target) > fit_distance(points, c.target, v, c.up, tan_v, aspect, 0.8f)) {
        c.eye = c.target - v * fit_distance(points, c.target, v, c.up, tan_v, aspect, 0.92f);
        finish_camera(c, b, size);
    }
    return c;
}

Camera frame_bounds(const Bounds& b0, glm::ivec2 size, float fov_y_deg) {
    Bounds b = b0.valid() ? b0 : Bounds{glm::vec3(-1), glm::vec3(1)};
    glm::vec3 ext = b.hi - b.lo;
    int thin = 0;
    for (int i = 1; i < 3; ++i)
        if (ext[i] < ext[thin]) thin = i;
    int up_axis = (thin + 1) % 3, other = (thin + 2) % 3;
    if (ext[other] > ext[up_axis]) std::swap(up_axis, other);
    // A wide image wants the long axis horizontal unless the data is much taller than wide.
    Camera c;
    c.fov_y_deg = fov_y_deg;
    c.target = b.center();
    glm::vec3 view_dir(0.0f);
    view_dir[thin] = 1.0f;
    c.up = glm::vec3(0.0f);
    c.up[up_axis] = 1.0f;
    float aspect = size.y > 0 ? float(size.x) / float(size.y) : 1.0f;
    // Distance so the bounding sphere fits both vertically and horizontally.
    float r = b.radius() > 0.0f ? b.radius() : 1.0f;
    float half_v = glm::radians(fov_y_deg) * 0.5f;
    float half_h = std::atan(std::tan(half_v) * aspect);
    float dist = r / std::sin(std::min(half_v, half_h)) * 0.92f;
    c.eye = c.target - view_dir * dist;
    finish_camera(c, b, size);
    return c;
}

Camera frame_bounds_orbit(const Bounds& b0, const std::vector<glm::vec3>& points0, glm::ivec2 size, float fov_y_deg,
                          float fill) {
    const Bounds b = b0.valid() ? b0 : Bounds{glm::vec3(-1), glm::vec3(1)};
    const std::vector<glm::vec3> points = points0.empty() ? corners(b) : points0;
    Camera c = frame_bounds(b, size, fov_y_deg);
    const glm::vec3 up = glm::normalize(c.up);
    const glm::vec3 dir0 = glm::normalize(c.target - c.eye);
    const float aspect = size.y > 0 ? float(size.x) / float(size.y) : 1.0f;
    const float tan_v = std::tan(glm::radians(fov_y_deg) * 0.5f);
    // Every 1 degree of the turn; between two the box moves less than the margin `fill` leaves.
    float dist = 0.0f;
    for (int deg = 0; deg < 360; ++deg) {
        const glm::mat4 rot = glm::rotate(glm::mat4(1.0f), glm::radians(float(deg)), up);
        dist = std::max(dist, fit_distance(points, c.target, glm::vec3(rot * glm::vec4(dir0, 0.0f)), up, tan_v, aspect, fill));
    }
    c.eye = c.target - dir0 * dist;
    finish_camera(c, b, size);
    return c;
}

Camera orbit(const Camera& base, double deg_per_s, double t, const Bounds& b, glm::ivec2 size) {
    Camera c = base;
    glm::mat4 rot = glm::rotate(glm::mat4(1.0f), float(glm::radians(deg_per_s * t)), glm::normalize(base.up));
    c.eye = base.target + glm::vec3(rot * glm::vec4(base.eye - base.target, 0.0f));
    finish_camera(c, b, size);
    return c;
}

namespace {
glm::vec3 vec3_at(const json& j, const std::string& key, const std::string& where, glm::vec3 def, bool required) {
    if (!j.contains(key)) {
        if (required) throw DataError(where + "/" + key + ": missing (expected [x, y, z])");
        return def;
    }
    const json& v = j[key];
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
        throw DataError(where + "/" + key + ": expected [x, y, z], got " + v.dump());
    const double cap = io::max_coordinate();  // the data's own limit: beyond it a float overflows the maths
    for (int i = 0; i < 3; ++i)
        if (!(std::fabs(v[i].get<double>()) <= cap))
            throw DataError(where + "/" + key + "/" + std::to_string(i) + ": " + v[i].dump() +
                            " is beyond the coordinate cap (PATHLET_MAX_COORDINATE)");
    return {v[0].get<float>(), v[1].get<float>(), v[2].get<float>()};
}
glm::vec3 catmull_rom(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, float s) {
    float s2 = s * s, s3 = s2 * s;
    return 0.5f * ((2.0f * p1) + (-p0 + p2) * s + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * s2 +
                   (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * s3);
}
}  // namespace

CameraPath CameraPath::parse(const std::string& text, const std::string& path) {
    const json j = text::parse_json_of(path, text, "camera path");
    if (!j.is_object() || !j.contains("keyframes") || !j["keyframes"].is_array() || j["keyframes"].empty())
        throw DataError(path + ":/keyframes: expected a non-empty array of {time, eye, target, up, fov}");
    CameraPath cp;
    for (size_t i = 0; i < j["keyframes"].size(); ++i) {
        const json& k = j["keyframes"][i];
        std::string where = path + ":/keyframes/" + std::to_string(i);
        if (!k.is_object()) throw DataError(where + ": expected an object");
        if (!k.contains("time") || !k["time"].is_number()) throw DataError(where + "/time: missing or not a number");
        Key key;
        key.time = k["time"].get<double>();
        key.eye = vec3_at(k, "eye", where, {}, true);
        key.target = vec3_at(k, "target", where, {}, true);
        key.up = vec3_at(k, "up", where, {0, 0, 1}, false);
        key.fov = k.contains("fov") && k["fov"].is_number() ? k["fov"].get<float>() : 40.0f;
        if (!(key.fov > 1.0f && key.fov < 179.0f)) throw DataError(where + "/fov: must be in (1, 179) degrees");
        if (glm::length(key.eye - key.target) < 1e-9f) throw DataError(where + ": eye and target coincide");
        if (!cp.keys_.empty() && key.time <= cp.keys_.back().time)
            throw DataError(where + "/time: keyframe times must increase");
        cp.keys_.push_back(key);
    }
    return cp;
}

CameraPath CameraPath::load(const std::string& path) {
    return parse(text::read_json_text(path, "camera path"), path);
}

Camera CameraPath::at(double t, const Bounds& b, glm::ivec2 size) const {
    Camera c;
    size_t n = keys_.size();
    if (n == 1 || t <= keys_.front().time) {
        const Key& k = keys_.front();
        c.eye = k.eye, c.target = k.target, c.up = k.up, c.fov_y_deg = k.fov;
    } else if (t >= keys_.back().time) {
        const Key& k = keys_.back();
        c.eye = k.eye, c.target = k.target, c.up = k.up, c.fov_y_deg = k.fov;
    } else {
        size_t i = 0;
        while (i + 1 < n && keys_[i + 1].time <= t) ++i;
        const Key& k1 = keys_[i];
        const Key& k2 = keys_[i + 1];
        const Key& k0 = keys_[i > 0 ? i - 1 : i];
        const Key& k3 = keys_[std::min(i + 2, n - 1)];
        float s = float((t - k1.time) / (k2.time - k1.time));
        c.eye = catmull_rom(k0.eye, k1.eye, k2.eye, k3.eye, s);
        c.target = catmull_rom(k0.target, k1.target, k2.target, k3.target, s);
        c.up = glm::normalize(glm::mix(k1.up, k2.up, s));
        c.fov_y_deg = k1.fov + (k2.fov - k1.fov) * s;
    }
    finish_camera(c, b, size);
    return c;
}

}  // namespace pathlet
