// gbuffer: the pathlets of the time window as view-aligned tube quads (shaders/line_quad.geom)
// into LineAO's inputs: colour map, normal + linear depth, zoom, depth, optionally line ids.
#include "line_pass.hpp"

#include <pathlet/plugin.hpp>

namespace {

namespace lp = pathlet::line_pass;

class GBuffer : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        write_id_ = ctx.connected("line_id");  // an optional output: written only when a graph binds it
        std::vector<std::string> defines;
        if (write_id_) defines.push_back("WRITE_LINE_ID");
        prog_ = &ctx.program({"gbuffer.vert", "line_quad.geom", "gbuffer.frag"}, defines);
    }

    void execute(pathlet::PassContext& ctx) override {
        std::vector<std::string> targets{"color", "normal_depth", "zoom"};
        if (write_id_) targets.push_back("line_id");
        ctx.bind_framebuffer(targets, "depth");

        // Background values are part of the contract with lineao: colour alpha 0, normal 0,
        // depth 1, zoom 0, line id -1.
        lp::prepare_clear();
        GLuint fbo = lp::bound_framebuffer();
        glm::vec3 bg = ctx.params().v3("background");
        const float color[4] = {bg.x, bg.y, bg.z, 0.0f};
        const float normal_depth[4] = {0.0f, 0.0f, 0.0f, 1.0f};
        const float zoom[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        const GLint no_id[4] = {-1, 0, 0, 0};
        const float far = 1.0f;
        glClearNamedFramebufferfv(fbo, GL_COLOR, 0, color);
        glClearNamedFramebufferfv(fbo, GL_COLOR, 1, normal_depth);
        glClearNamedFramebufferfv(fbo, GL_COLOR, 2, zoom);
        if (write_id_) glClearNamedFramebufferiv(fbo, GL_COLOR, 3, no_id);
        glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &far);

        prog_->use();
        const pathlet::Camera& cam = ctx.camera();
        prog_->set("u_zoom_scale", 0.5f * float(ctx.output_size().y) * cam.proj[1][1]);
        lp::draw(ctx, *prog_, ranges_);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    pathlet::GpuScene::Ranges ranges_;  // reused every frame
    bool write_id_ = false;
};

pathlet::PassTypeInfo gbuffer_type() {
    pathlet::PassTypeBuilder b("gbuffer",
                               "pathlets of the time window as view-aligned tube quads with halos and a speed colour "
                               "map, written as LineAO's G-buffer (colour, normal + linear depth, zoom, depth)");
    lp::declare_params(b)
        .output_texture("color", "rgba8", "line colour incl. halos; background: `background` with alpha 0")
        .output_texture("normal_depth", "rgba16f",
                        "xyz: view-space unit tube normal; w: linear depth (-z_eye - near) / (far - near); "
                        "background: (0, 0, 0, 1)")
        .output_texture("zoom", "r32f", "pixels per world unit at the fragment, (H/2) P[1][1] / -z_eye; background 0")
        .output_texture("depth", "depth24", "z-buffer of the tube surfaces (halos pushed back)")
        .output_texture("line_id", "r32i", "line index per pixel, -1 on background (bind it to get it)", 1, 1.0f,
                        /*optional=*/true);
    return b.make<GBuffer>();
}

}  // namespace

PATHLET_PLUGIN("gbuffer", { sink->add(gbuffer_type()); })
