// The line kit's G-buffer pass: the pathlets of the time window as view-aligned tube quads
// through the pass's hooks into LineAO's inputs.
#include <pathlet/lines.hpp>

#include <algorithm>

namespace pathlet::lines {

namespace {
// The optional outputs, in attachment order after color, normal_depth and zoom, with their
// background values (the contract with lineao and edge_aa: line id -1, edge alpha 0 = no line).
struct OptionalTarget {
    const char* pin;
    const char* macro;  // WRITE_<macro> and <macro>_LOCATION in line_gbuffer.frag
    glm::vec4 clear;
    bool integer;
};
const OptionalTarget kOptional[] = {
    {"line_id", "LINE_ID", glm::vec4(-1, 0, 0, 0), true},
    {"edge", "EDGE", glm::vec4(0.5f, 0.5f, 1.0f, 0.0f), false},
    {"tangent", "TANGENT", glm::vec4(0.0f), false},
};
}  // namespace

void GBufferPass::setup(PassContext& ctx) {
    // Optional outputs are written only when a graph binds them; each gets the next location.
    targets_ = {"color", "normal_depth", "zoom"};
    std::vector<std::string> defines;
    for (const OptionalTarget& t : kOptional)
        if (ctx.connected(t.pin)) {
            defines.push_back(std::string("WRITE_") + t.macro);
            defines.push_back(std::string(t.macro) + "_LOCATION " + std::to_string(targets_.size()));
            targets_.push_back(t.pin);
        }
    prog_ = &program(ctx, {"line_gbuffer.frag"}, hooks(ctx), defines);
}

void GBufferPass::execute(PassContext& ctx) {
    ctx.bind_framebuffer(targets_, "depth");

    // Background values are part of the contract with lineao: colour alpha 0, normal 0,
    // depth 1, zoom 0.
    glm::vec3 bg = ctx.params().v3("background");
    clear_color(0, glm::vec4(bg, 0.0f));
    clear_color(1, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    clear_color(2, glm::vec4(0.0f));
    for (const OptionalTarget& t : kOptional) {
        const auto at = std::find(targets_.begin(), targets_.end(), t.pin);
        if (at == targets_.end()) continue;
        const int i = int(at - targets_.begin());
        if (t.integer) clear_color_int(i, glm::ivec4(t.clear));
        else clear_color(i, t.clear);
    }
    clear_depth(1.0f);

    prog_->use();
    prog_->set("u_zoom_scale", 0.5f * float(ctx.output_size().y) * ctx.camera().proj[1][1]);
    set_uniforms(ctx, *prog_);
    drawer_.draw(ctx, *prog_);
}

}  // namespace pathlet::lines
