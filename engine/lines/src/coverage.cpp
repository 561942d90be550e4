// lines::Coverage: the optional "coverage" depth of the passes that draw every fragment.
#include <pathlet/lines.hpp>
#include <pathlet/shader.hpp>

namespace pathlet::lines {

Coverage::Coverage(const PassContext& ctx) : connected_(ctx.connected(kPin)) {}

void Coverage::clear() const {
    if (!connected_) return;
    const float far = 1.0f;
    glDepthMask(GL_TRUE);
    glClearBufferfv(GL_DEPTH, 0, &far);
}

void Coverage::draw(PassContext& ctx, ShaderProgram& prog) const {
    if (connected_) {
        // llvmpipe runs a fullscreen shader on every block the draw covers, depth-tested or not:
        // the scissor skips the border around the data (62 -> 40 ms at 720p, variant2_oit_ao).
        ctx.draw_fullscreen(prog, screen_rect(ctx, 2), kPin);
    } else {
        prog.use();
        ctx.draw_fullscreen();
    }
}

}  // namespace pathlet::lines
