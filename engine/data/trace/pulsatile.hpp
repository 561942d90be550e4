// Pulsatile modulation of a steady field: velocity(t) = v_steady * factor(t).
// One cycle of `period` seconds, phase = (t mod period) / period:
//   systole  (phase < 0.35): factor = peak * (0.2 + 0.8 * sin^2(pi * phase / 0.35))
//                            -> rises from the diastolic floor to `peak` at phase 0.175
//   diastole (phase >= 0.35): factor = peak * 0.2, plus a small dicrotic bump
//                            0.1 * peak * sin(pi * (phase - 0.35) / 0.15) over phase 0.35..0.5
// The cycle mean is about 0.35 * peak, so peak ~ 2.85 keeps the mean flow of the steady field.
#pragma once

namespace pathlet::trace {

struct Pulsatile {
    float period = 1.0f;  // seconds per heart beat
    float peak = 1.0f;    // factor at peak systole
    float factor(float t) const;
};

}  // namespace pathlet::trace
