#pragma once
// Temporal flicker: how much the AO changes from frame to frame at pixels
// whose geometry barely changed, set against how much the geometry itself changed.
#include "frame_sample.hpp"

namespace pathlet::quality {

struct FlickerStats {
  std::size_t stable_pixels = 0;    // same line id in both frames, depth within tolerance
  std::size_t covered_pixels = 0;   // covered by a line in either frame
  double ao_flicker = 0;       // mean |AO(t) - AO(t-1)| over the stable pixels
  double geometry_change = 0;  // fraction of covered pixels whose line id or depth changed
};

// Throws std::invalid_argument when the frames differ in size or are incomplete.
FlickerStats measure_flicker(const FrameSample& prev, const FrameSample& cur, float depth_tolerance);
// Mean over consecutive pairs, weighted by stable pixels; needs at least two frames.
FlickerStats measure_flicker(const std::vector<FrameSample>& frames, float depth_tolerance);

// Flicker against a reference: AO that follows the scene must change where the
// scene's occlusion changes (pathlets advance every frame), so the plain measure cannot tell a
// faithful AO from a noisy one. Over the same stable pixels: how much the reference AO changes,
// and the mean |dAO - dRef|, the change that is not the reference's.
struct ReferenceFlicker {
  double reference_change = 0;  // mean |Ref(t) - Ref(t-1)|
  double excess = 0;            // mean |(AO(t) - AO(t-1)) - (Ref(t) - Ref(t-1))|
};
// `reference[k]` holds frame k's reference AO per pixel (frames' size). Throws as above.
ReferenceFlicker measure_flicker_against(const std::vector<FrameSample>& frames,
                                         const std::vector<std::vector<float>>& reference, float depth_tolerance);

}  // namespace pathlet::quality
