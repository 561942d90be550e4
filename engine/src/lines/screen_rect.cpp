// The screen rectangle of the lines (lines::screen_rect): post passes skip the border around
// the data, which at the default framing of a tall vessel is most of a wide frame.
#include <pathlet/lines.hpp>

#include <algorithm>
#include <cmath>

namespace pathlet::lines {

glm::ivec4 screen_rect(const PassContext& ctx, int pad_px) {
    const glm::ivec2 size = ctx.output_size();
    const glm::ivec4 all(0, 0, size.x, size.y);
    const Bounds b = ctx.scene().bounds();
    if (!b.valid()) return all;
    const float pad = ctx.scene().auto_line_width() * 4.0f;  // wide lines and halos stay inside
    const glm::vec3 lo = b.lo - pad, hi = b.hi + pad;
    const glm::mat4 clip = ctx.camera().proj * ctx.camera().view;
    glm::vec2 mn(1e30f), mx(-1e30f);
    for (int i = 0; i < 8; ++i) {
        const glm::vec4 c = clip * glm::vec4(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z, 1.0f);
        if (!(c.w > 1e-6f)) return all;  // a corner behind the eye: the projection folds over
        const glm::vec2 ndc = glm::vec2(c) / c.w;
        mn = glm::min(mn, ndc);
        mx = glm::max(mx, ndc);
    }
    const glm::vec2 s(size);
    const glm::ivec2 p0 = glm::ivec2(glm::floor((mn * 0.5f + 0.5f) * s)) - pad_px;
    const glm::ivec2 p1 = glm::ivec2(glm::ceil((mx * 0.5f + 0.5f) * s)) + pad_px;
    const glm::ivec2 a = glm::clamp(p0, glm::ivec2(0), size), z = glm::clamp(p1, glm::ivec2(0), size);
    if (z.x <= a.x || z.y <= a.y) return glm::ivec4(0);
    return glm::ivec4(a, z);
}

}  // namespace pathlet::lines
