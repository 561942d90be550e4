#include "ao_error.hpp"

#include <cmath>
#include <stdexcept>

namespace pathlet::quality {

AoError measure_ao_error(const FrameSample& frame, const std::vector<float>& reference) {
  if (reference.size() != frame.size() || frame.ao.size() != frame.size() ||
      frame.line_id.size() != frame.size())
    throw std::invalid_argument("ao error: reference and frame differ in size");
  AoError e;
  e.abs_error.assign(frame.size(), 0.0f);
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, sum = 0;
  for (size_t i = 0; i < frame.size(); ++i) {
    if (frame.line_id[i] < 0) continue;
    const double a = frame.ao[i], b = reference[i];
    e.abs_error[i] = float(std::fabs(a - b));
    sum += std::fabs(a - b);
    sa += a; sb += b; saa += a * a; sbb += b * b; sab += a * b;
    ++e.pixels;
  }
  if (!e.pixels) return e;
  const double n = double(e.pixels);
  e.mae = sum / n;
  const double va = saa - sa * sa / n, vb = sbb - sb * sb / n, cov = sab - sa * sb / n;
  e.correlation = (va > 1e-12 && vb > 1e-12) ? cov / std::sqrt(va * vb) : 0.0;
  return e;
}

}  // namespace pathlet::quality
