// temporal_ao: makes LineAO temporally stable in animation. Blends this frame's AO
// with last frame's accumulated AO where the pixel, reprojected with last frame's camera, shows
// the same line at the expected depth; elsewhere (disocclusion, another line in front, first
// frame) the history is dropped. Keeps last frame's camera itself, so a moving camera works too.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>

namespace {

class TemporalAo : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        compute_ = ctx.use_compute();
        prog_ = &ctx.fullscreen_program("temporal_ao.frag");
        have_prev_ = false;  // a resize or parameter change starts over
    }

    void execute(pathlet::PassContext& ctx) override {
        const auto& p = ctx.params();
        const pathlet::Camera& cam = ctx.camera();
        if (!have_prev_) prev_ = cam;
        prog_->use();
        prog_->set("u_cur_to_prev_view", prev_.view * glm::inverse(cam.view));
        prog_->set("u_prev_proj", prev_.proj);
        prog_->set("u_proj_scale", glm::vec2(cam.proj[0][0], cam.proj[1][1]));
        prog_->set("u_near_far", glm::vec2(cam.near_plane, cam.far_plane));
        prog_->set("u_prev_near_far", glm::vec2(prev_.near_plane, prev_.far_plane));
        prog_->set("u_history_valid", (have_prev_ && p.b("enabled")) ? 1 : 0);
        ctx.stat(pathlet::kComputeStat, compute_ ? 1.0 : 0.0);
        if (ctx.connected("depth")) {
            // Only covered pixels: background AO is never read (bilateral skips it, and the
            // history is read only where the line id matches). They lie in the lines' screen
            // rectangle: the compute version would otherwise test every pixel's depth (llvmpipe,
            // 1280x720: 105-132 ms against the fragment's 8-19, whose early depth test skips tiles).
            const glm::ivec4 rect = pathlet::lines::screen_rect(ctx, 2);
            if (compute_) {
                ctx.dispatch_fullscreen(*prog_, rect, "depth");
            } else {
                ctx.bind_framebuffer({"ao_acc"}, "depth");
                ctx.draw_fullscreen(*prog_, rect, "depth");
            }
        } else if (compute_) {
            ctx.dispatch_fullscreen(*prog_);
        } else {
            ctx.bind_framebuffer({"ao_acc"});
            ctx.draw_fullscreen();
        }
        prev_ = cam;
        have_prev_ = true;
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    pathlet::Camera prev_;
    bool have_prev_ = false;
    bool compute_ = false;
};

pathlet::PassTypeInfo temporal_ao_type() {
    return pathlet::PassTypeBuilder("temporal_ao",
                                    "reprojected temporal accumulation of AO, history rejected by line id and depth")
        .param_float("alpha", 0.15, 0.0, 1.0, "weight of this frame's AO (1 = no accumulation)")
        .param_float("depth_tolerance", 0.01, 0.0, 1.0,
                     "largest change of normalised linear depth that still counts as the same surface")
        .param_bool("enabled", true, "false: pass this frame's AO through")
        .input_texture("ao", "r16f", "this frame's AO (1 = unoccluded)")
        .input_texture("ao_prev", "r16f", "last frame's accumulated AO: the output's history (ao_acc@prev)")
        .input_texture("normal_depth", "rgba16f", "view-space normal (xyz), normalised linear depth (w)")
        .input_texture("normal_depth_prev", "rgba16f", "last frame's normal_depth (normal_depth@prev)")
        .input_texture("line_id", "r32i", "line id per pixel, -1 on background (gbuffer's line_id)")
        .input_texture("line_id_prev", "r32i", "last frame's line id (line_id@prev)")
        .input_texture("depth", "depth24", "G-buffer depth; when connected, background pixels are skipped",
                       {.optional = true})
        .output_texture("ao_acc", "r16f", "accumulated AO; make it a history resource")
        .compute_version()
        .make<TemporalAo>();
}

}  // namespace

PATHLET_PLUGIN("temporal_ao", { sink->add(temporal_ao_type()); })
