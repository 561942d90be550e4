// The line kit's G-buffer pass: the pathlets of the time window as view-aligned tube quads
// into LineAO's inputs. `gbuffer` is this pass without hooks; fades subclass it.
#include <pathlet/lines.hpp>

namespace pathlet::lines {

void GBufferPass::setup(PassContext& ctx) {
    write_id_ = ctx.connected("line_id");  // an optional output: written only when a graph binds it
    std::vector<std::string> defines;
    if (write_id_) defines.push_back("WRITE_LINE_ID");
    write_edge_ = ctx.connected("edge");
    if (write_edge_) {
        defines.push_back("WRITE_EDGE");
        defines.push_back("EDGE_LOCATION " + std::to_string(write_id_ ? 4 : 3));
    }
    write_tangent_ = ctx.connected("tangent");
    if (write_tangent_) {
        defines.push_back("WRITE_TANGENT");
        defines.push_back("TANGENT_LOCATION " + std::to_string(3 + int(write_id_) + int(write_edge_)));
    }
    prog_ = &program(ctx, {"line_gbuffer.frag"}, hooks_, defines);
}

void GBufferPass::execute(PassContext& ctx) {
    std::vector<std::string> targets{"color", "normal_depth", "zoom"};
    if (write_id_) targets.push_back("line_id");
    if (write_edge_) targets.push_back("edge");
    if (write_tangent_) targets.push_back("tangent");
    ctx.bind_framebuffer(targets, "depth");

    // Background values are part of the contract with lineao: colour alpha 0, normal 0,
    // depth 1, zoom 0, line id -1.
    glm::vec3 bg = ctx.params().v3("background");
    clear_color(0, glm::vec4(bg, 0.0f));
    clear_color(1, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    clear_color(2, glm::vec4(0.0f));
    if (write_id_) clear_color_int(3, glm::ivec4(-1, 0, 0, 0));
    if (write_edge_) clear_color(write_id_ ? 4 : 3, glm::vec4(0.5f, 0.5f, 1.0f, 0.0f));  // alpha 0: no line
    if (write_tangent_) clear_color(3 + int(write_id_) + int(write_edge_), glm::vec4(0.0f));
    clear_depth(1.0f);

    prog_->use();
    prog_->set("u_zoom_scale", 0.5f * float(ctx.output_size().y) * ctx.camera().proj[1][1]);
    set_uniforms(ctx, *prog_);
    drawer_.draw(ctx, *prog_);
}

}  // namespace pathlet::lines
