// The screen rectangle of the lines (lines::screen_rect): post passes skip the border around
// the data, which at the default framing of a tall vessel is most of a wide frame.
#include <pathlet/lines.hpp>

#include <algorithm>
#include <cmath>

namespace pathlet::lines {

glm::ivec4 screen_rect(const PassContext& ctx, int pad_px) {
    return screen_rect(ctx.scene(), ctx.camera(), ctx.output_size(), pad_px);
}

glm::ivec4 screen_rect(const GpuScene& scene, const Camera& camera, glm::ivec2 size, int pad_px) {
    const glm::ivec4 all(0, 0, size.x, size.y);
    const Bounds b = scene.bounds();
    if (!b.valid()) return all;
    // The widest quad's half width (a width hook may widen it kMaxWidthHook times), plus a
    // quarter for the box's corners seen at an angle; halos lie inside the quad.
    const float widest_half = 0.5f * scene.widest_line() * GpuScene::kMaxWidthHook;
    const float pad = std::max(scene.auto_line_width() * 4.0f, 1.25f * widest_half);
    const glm::vec3 lo = b.lo - pad, hi = b.hi + pad;
    const glm::mat4 clip = camera.proj * camera.view;
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

ScopedScissor::ScopedScissor(glm::ivec4 r) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(r.x, r.y, std::max(r.z - r.x, 0), std::max(r.w - r.y, 0));
}

ScopedScissor::~ScopedScissor() { glDisable(GL_SCISSOR_TEST); }

glm::ivec4 rect_at_level(glm::ivec4 r, int level, int pad_px, glm::ivec2 size) {
    const int f = 1 << std::clamp(level, 0, 30);
    const glm::ivec2 a = glm::ivec2(r.x, r.y) / f - pad_px;                // floor (r >= 0)
    const glm::ivec2 z = (glm::ivec2(r.z, r.w) + (f - 1)) / f + pad_px;  // ceil
    const glm::ivec2 a2 = glm::clamp(a, glm::ivec2(0), size), z2 = glm::clamp(z, glm::ivec2(0), size);
    return {a2, z2};
}

}  // namespace pathlet::lines
