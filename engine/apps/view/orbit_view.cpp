#include "view/orbit_view.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace pathlet::view {

OrbitView::OrbitView(const Camera& framing, const Bounds& bounds, glm::ivec2 size)
    : base_(framing), cur_(framing), bounds_(bounds), size_(size) {}

void OrbitView::orbit(float dx_px, float dy_px) {
    const glm::vec3 up = glm::normalize(cur_.up);
    glm::vec3 off = cur_.eye - cur_.target;
    off = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(-0.4f * dx_px), up) * glm::vec4(off, 0.0f));
    const glm::vec3 right = glm::normalize(glm::cross(-off, up));
    glm::vec3 tilted = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(-0.4f * dy_px), right) * glm::vec4(off, 0.0f));
    if (std::fabs(glm::dot(glm::normalize(tilted), up)) < 0.985f) off = tilted;  // stop short of the poles
    cur_.eye = cur_.target + off;
    finish_camera(cur_, bounds_, size_);
}

void OrbitView::pan(float dx_px, float dy_px) {
    const glm::vec3 fwd = cur_.target - cur_.eye;
    const float d = glm::length(fwd);
    const glm::vec3 right = glm::normalize(glm::cross(fwd, cur_.up));
    const glm::vec3 cam_up = glm::normalize(glm::cross(right, fwd));
    const float world_per_px = 2.0f * d * std::tan(glm::radians(cur_.fov_y_deg) * 0.5f) / float(std::max(size_.y, 1));
    const glm::vec3 move = (-dx_px * right + dy_px * cam_up) * world_per_px;
    cur_.eye += move;
    cur_.target += move;
    finish_camera(cur_, bounds_, size_);
}

void OrbitView::zoom(float steps) {
    const glm::vec3 off = cur_.eye - cur_.target;
    const float r = std::max(bounds_.radius(), 1e-3f);
    const float d = std::clamp(glm::length(off) / std::pow(1.15f, steps), 0.01f * r, 100.0f * r);
    cur_.eye = cur_.target + glm::normalize(off) * d;
    finish_camera(cur_, bounds_, size_);
}

void Playback::advance(double wall_s) {
    if (!playing || !(t_max > t_min)) return;
    t += wall_s * speed;
    const double span = t_max - t_min;
    if (t > t_max || t < t_min) {
        if (loop) t = t_min + std::fmod(std::fmod(t - t_min, span) + span, span);
        else t = std::clamp(t, t_min, t_max), playing = false;
    }
}

void Playback::scrub(double data_s) { t = std::clamp(t + data_s, t_min, std::max(t_min, t_max)); }

}  // namespace pathlet::view
