// volume_ao: object-space line AO per pixel of the G-buffer from the line-density volume
// (line_density), issue 25. The estimate itself is the line kit's (line_volume_ao.glsl), so a
// line pass that shades its own fragments (fill_list under OIT) computes the same AO.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

#include <string>
#include <vector>

namespace {

namespace lines = pathlet::lines;

class VolumeAoPass : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        std::vector<std::string> defines = lines::VolumeAo::defines(ctx);
        if (ctx.connected("screen_ao")) defines.push_back("SCREEN_AO");
        compute_ = ctx.use_compute();
        prog_ = &ctx.fullscreen_program("volume_ao.frag", defines);
    }

    void execute(pathlet::PassContext& ctx) override {
        prog_->use();  // normal_depth, tangent, screen_ao and screen_weight by declaration
        vao_.bind(ctx, *prog_);
        const float one = 1.0f;
        glClearTexImage(ctx.texture("ao").id, 0, GL_RED, GL_FLOAT, &one);  // background stays 1
        ctx.stat("samples per pixel", double(ctx.params().i("directions") * ctx.params().i("steps")));
        ctx.stat(pathlet::kComputeStat, compute_ ? 1.0 : 0.0);
        if (compute_) {
            ctx.dispatch_fullscreen(*prog_, lines::screen_rect(ctx, 2), ctx.connected("depth") ? "depth" : "");
            return;
        }
        lines::ScopedScissor clip(lines::screen_rect(ctx, 2));
        if (ctx.connected("depth")) {
            ctx.bind_framebuffer({"ao"}, "depth");
            ctx.draw_fullscreen_on_geometry(*prog_);
        } else {
            ctx.bind_framebuffer({"ao"});
            ctx.draw_fullscreen();
        }
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    lines::VolumeAo vao_;
    bool compute_ = false;
};

pathlet::PassTypeInfo volume_ao_type() {
    pathlet::PassTypeBuilder b("volume_ao",
                               "object-space line AO per pixel from the line-density volume: cosine-weighted rays "
                               "through the density, the line's own tube left out; 1 = unoccluded");
    lines::declare_line_width_params(b);
    lines::declare_volume_ao_params(b)
        .param_float("screen_weight", 0.5, 0.0, 1.0,
                     "with screen_ao connected (the hybrid): AO x mix(1, screen_ao, screen_weight)")
        .input_buffer("density", "the line-density volume (line_density)")
        .input_texture("normal_depth", "rgba16f", "view-space normal (xyz), normalised linear depth (w); its line pass's "
                       "line_width and width_factor must be this pass's",
                       {.same_params = {"line_width", "width_factor"}})
        .input_texture("tangent", "rgba16f", "the G-buffer's tangent target: tangent (xyz), eye depth to the axis (w)")
        .input_texture("depth", "depth24", "G-buffer depth; when connected, background pixels are skipped",
                       {.optional = true})
        .input_texture("screen_ao", "r16f", "a screen-space AO term (lineao's) to multiply in: the hybrid",
                       {.optional = true})
        .output_texture("ao", "r16f", "the AO term, 1 on background")
        .compute_version();
    return b.make<VolumeAoPass>();
}

}  // namespace

PATHLET_PLUGIN("volume_ao", { sink->add(volume_ao_type()); })
