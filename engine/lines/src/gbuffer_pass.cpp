// The line kit's G-buffer pass: the pathlets of the time window as view-aligned tube quads
// through the pass's hooks into LineAO's inputs; and the G-buffer targets, shared with any pass
// that writes them (fill_list writes variant 2's in the raster of its lists).
#include <pathlet/lines.hpp>

#include <iterator>

namespace pathlet::lines {

namespace {
// Every colour target of the G-buffer in attachment order, with its background value (the
// contract with lineao, edge_aa and volume_ao: normal 0 and depth 1, zoom 0, line id -1, edge
// alpha 0 = no line). The colour's background is the pass's `background` parameter.
struct Target {
    const char* pin;
    const char* macro;  // WRITE_<macro> and <macro>_LOCATION in line_gbuffer_out.glsl
    glm::vec4 clear;
    bool integer;
    bool background = false;  // cleared to the pass's `background` (alpha 0) instead
};
const Target kTargets[] = {
    {"color", "COLOR", glm::vec4(0.0f), false, true},
    {"normal_depth", "NORMAL_DEPTH", glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), false},
    {"zoom", "ZOOM", glm::vec4(0.0f), false},
    {"line_id", "LINE_ID", glm::vec4(-1, 0, 0, 0), true},
    {"edge", "EDGE", glm::vec4(0.5f, 0.5f, 1.0f, 0.0f), false},
    {"tangent", "TANGENT", glm::vec4(0.0f), false},
};
}  // namespace

GBufferTargets gbuffer_targets(const PassContext& ctx) {
    // Only the targets a graph binds are written; each gets the next location.
    GBufferTargets t;
    for (int row = 0; row < int(std::size(kTargets)); ++row) {
        const Target& g = kTargets[row];
        if (!ctx.connected(g.pin)) continue;
        t.defines.push_back(std::string("WRITE_") + g.macro);
        t.defines.push_back(std::string(g.macro) + "_LOCATION " + std::to_string(t.pins.size()));
        t.pins.push_back(g.pin);
        t.rows.push_back(row);
    }
    return t;
}

void bind_gbuffer(PassContext& ctx, const GBufferTargets& t, const ShaderProgram& prog) {
    ctx.bind_framebuffer(t.pins, "depth");
    const glm::vec4 bg(ctx.params().v3("background"), 0.0f);
    for (size_t i = 0; i < t.rows.size(); ++i) {
        const Target& g = kTargets[t.rows[i]];
        if (g.integer) clear_color_int(int(i), glm::ivec4(g.clear));
        else clear_color(int(i), g.background ? bg : g.clear);
    }
    clear_depth(1.0f);
    prog.use();
    prog.set("u_zoom_scale", 0.5f * float(ctx.output_size().y) * ctx.camera().proj[1][1]);
}

void GBufferPass::setup(PassContext& ctx) {
    targets_ = gbuffer_targets(ctx);
    std::vector<std::string> defines = targets_.defines;
    for (auto& d : fragment_defines(ctx)) defines.push_back(std::move(d));
    prog_ = &program(ctx, {"line_gbuffer.frag"}, hooks(ctx), defines);
}

void GBufferPass::execute(PassContext& ctx) {
    bind_gbuffer(ctx, targets_, *prog_);
    set_uniforms(ctx, *prog_);
    drawer_.draw(ctx, *prog_);
}

}  // namespace pathlet::lines
