#include "flicker.hpp"

#include <cmath>
#include <stdexcept>

namespace pathlet::quality {

static void check(const FrameSample& f) {
  if (f.width <= 0 || f.height <= 0 || f.ao.size() != f.size() || f.line_id.size() != f.size() ||
      f.depth.size() != f.size())
    throw std::invalid_argument("flicker: frame buffers do not match its size");
}

FlickerStats measure_flicker(const FrameSample& prev, const FrameSample& cur, float depth_tolerance) {
  check(prev);
  check(cur);
  if (prev.width != cur.width || prev.height != cur.height)
    throw std::invalid_argument("flicker: frames differ in size");
  FlickerStats s;
  double sum = 0;
  size_t changed = 0;
  for (size_t i = 0; i < cur.size(); ++i) {
    const bool a = prev.line_id[i] >= 0, b = cur.line_id[i] >= 0;
    if (!a && !b) continue;
    ++s.covered_pixels;
    if (a && b && prev.line_id[i] == cur.line_id[i] &&
        std::fabs(prev.depth[i] - cur.depth[i]) <= depth_tolerance) {
      ++s.stable_pixels;
      sum += std::fabs(double(cur.ao[i]) - double(prev.ao[i]));
    } else {
      ++changed;
    }
  }
  s.ao_flicker = s.stable_pixels ? sum / double(s.stable_pixels) : 0.0;
  s.geometry_change = s.covered_pixels ? double(changed) / double(s.covered_pixels) : 0.0;
  return s;
}

FlickerStats measure_flicker(const std::vector<FrameSample>& frames, float depth_tolerance) {
  if (frames.size() < 2) throw std::invalid_argument("flicker: needs at least two frames");
  FlickerStats total;
  double weighted = 0, geometry = 0;
  for (size_t k = 1; k < frames.size(); ++k) {
    const FlickerStats s = measure_flicker(frames[k - 1], frames[k], depth_tolerance);
    total.stable_pixels += s.stable_pixels;
    total.covered_pixels += s.covered_pixels;
    weighted += s.ao_flicker * double(s.stable_pixels);
    geometry += s.geometry_change;
  }
  total.ao_flicker = total.stable_pixels ? weighted / double(total.stable_pixels) : 0.0;
  total.geometry_change = geometry / double(frames.size() - 1);
  return total;
}

ReferenceFlicker measure_flicker_against(const std::vector<FrameSample>& frames,
                                         const std::vector<std::vector<float>>& reference, float depth_tolerance) {
  if (frames.size() < 2) throw std::invalid_argument("flicker: needs at least two frames");
  if (reference.size() != frames.size()) throw std::invalid_argument("flicker: one reference per frame");
  for (size_t k = 0; k < frames.size(); ++k) {
    check(frames[k]);
    if (reference[k].size() != frames[k].size() || frames[k].width != frames[0].width ||
        frames[k].height != frames[0].height)
      throw std::invalid_argument("flicker: frames and references differ in size");
  }
  ReferenceFlicker r;
  double change = 0, excess = 0;
  size_t n = 0;
  for (size_t k = 1; k < frames.size(); ++k) {
    const FrameSample &a = frames[k - 1], &b = frames[k];
    for (size_t i = 0; i < b.size(); ++i) {
      if (a.line_id[i] < 0 || a.line_id[i] != b.line_id[i] || std::fabs(a.depth[i] - b.depth[i]) > depth_tolerance)
        continue;
      const double d_ref = double(reference[k][i]) - double(reference[k - 1][i]);
      change += std::fabs(d_ref);
      excess += std::fabs(double(b.ao[i]) - double(a.ao[i]) - d_ref);
      ++n;
    }
  }
  if (n) r.reference_change = change / double(n), r.excess = excess / double(n);
  return r;
}

}  // namespace pathlet::quality
