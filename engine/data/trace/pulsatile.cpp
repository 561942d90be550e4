#include "pulsatile.hpp"

#include <cmath>

namespace pathlet::trace {

float Pulsatile::factor(float t) const {
    constexpr float kPi = 3.14159265358979f, kSystole = 0.35f, kFloor = 0.2f;
    float phase = period > 0.0f ? t / period : 0.0f;
    phase -= std::floor(phase);
    if (phase < kSystole) {
        const float s = std::sin(kPi * phase / kSystole);
        return peak * (kFloor + (1.0f - kFloor) * s * s);
    }
    float f = kFloor;
    if (phase < 0.5f) f += 0.1f * std::sin(kPi * (phase - kSystole) / 0.15f);
    return peak * f;
}

}  // namespace pathlet::trace
