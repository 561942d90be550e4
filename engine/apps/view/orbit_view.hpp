// The interactive camera and clock of `pathlet view`, kept free of GLFW so tests can drive them.
#pragma once

#include "camera.hpp"

namespace pathlet::view {

// Orbit about the target (left drag), pan (right or middle drag), zoom (wheel), reset. It
// starts from the render's framing, so an untouched view shows exactly what `render` writes.
class OrbitView {
public:
    OrbitView(const Camera& framing, const Bounds& bounds, glm::ivec2 size);
    void orbit(float dx_px, float dy_px);  // 0.4 degrees per pixel; never flips over the poles
    void pan(float dx_px, float dy_px);    // the point under the cursor (at the target's depth) follows it
    void zoom(float steps);                // each step 15 % closer (negative: farther)
    void reset() { cur_ = base_; }
    const Camera& camera() const { return cur_; }

private:
    Camera base_, cur_;
    Bounds bounds_;
    glm::ivec2 size_;
};

// Play/pause, scrub, speed and loop over the data's time span.
struct Playback {
    double t = 0, t_min = 0, t_max = 0;
    double speed = 1.0;  // data seconds per wall second
    bool playing = false, loop = true;
    void advance(double wall_s);  // while playing; wraps (loop) or stops at the end
    void scrub(double data_s);    // clamped to the span
};

}  // namespace pathlet::view
