// bilateral: removes LineAO's fixed noise pattern with a cross-bilateral filter guided by
// depth and normals (so AO does not leak between lines at different depths), then
// multiplies AO into the colour. Background pixels pass through untouched.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

class Bilateral : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        write_ao_ = ctx.connected("ao_smooth");  // optional: the smoothed AO alone, for per-fragment use
        std::vector<std::string> defines;
        if (write_ao_) defines.push_back("WRITE_AO");
        // The normal weight's power is compiled in (setup runs again when a parameter changes):
        // a whole power as products, 0 as no normal weight at all, else pow().
        const float power = ctx.params().f("normal_power");
        for (const auto& d : pathlet::whole_exponent("BILATERAL_NORMAL_POWER", power)) defines.push_back(d);
        if (power == 0.0f) defines.push_back("BILATERAL_NO_NORMAL");
        compute_ = ctx.use_compute();
        prog_ = &ctx.fullscreen_program("bilateral.frag", defines);
    }

    void execute(pathlet::PassContext& ctx) override {
        const auto& p = ctx.params();
        ctx.stat(pathlet::kComputeStat, compute_ ? 1.0 : 0.0);
        const float ss = std::max(p.f("sigma_spatial") * ctx.pixel_scale(), 1e-3f);
        prog_->set("u_inv2_sigma_s2", 1.0f / (2.0f * ss * ss));
        prog_->set("u_inv_sigma_d", 1.0f / std::max(p.f("sigma_depth"), 1e-6f));
        if (p.b("separable") && p.b("enabled")) {
            // Horizontal: ao -> tmp (filtered ao alone). Background texels of tmp are never read.
            prog_->set("u_step", glm::ivec2(1, 0));
            prog_->set("u_multiply", 0);
            draw(ctx, "tmp", false);
            prog_->bind_texture("u_ao", ctx.texture("tmp").id);
            prog_->set("u_step", glm::ivec2(0, 1));
        } else {
            prog_->set("u_step", glm::ivec2(0, 0));
        }
        prog_->set("u_multiply", 1);
        if (write_ao_) {
            const float one[4] = {1.0f, 1.0f, 1.0f, 1.0f};  // background: unoccluded
            glClearTexImage(ctx.texture("ao_smooth").id, 0, GL_RGBA, GL_FLOAT, one);
        }
        draw(ctx, "final", true);
    }

private:
    // Runs the filter into `out`, only on covered pixels when the G-buffer depth is
    // connected. For `final`, the background is the colour, copied first.
    void draw(pathlet::PassContext& ctx, const std::string& out, bool copy_background) {
        pathlet::Texture color = ctx.texture("color"), target = ctx.texture(out);
        bool skip = ctx.connected("depth") && (!copy_background || color.internal_format == target.internal_format);
        if (skip) {
            if (copy_background)
                glCopyImageSubData(color.id, GL_TEXTURE_2D, 0, 0, 0, 0, target.id, GL_TEXTURE_2D, 0, 0, 0, 0,
                                   target.width, target.height, 1);
            if (compute_) {  // the same pixels: the rectangle, on geometry
                ctx.dispatch_fullscreen(*prog_, pathlet::lines::screen_rect(ctx, 2), "depth");
                return;
            }
            ctx.bind_framebuffer(targets(out), "depth");
            // Covered pixels lie inside the lines' screen rectangle: tiles outside it are skipped.
            ctx.draw_fullscreen(*prog_, pathlet::lines::screen_rect(ctx, 2), "depth");
        } else if (compute_) {
            ctx.dispatch_fullscreen(*prog_);
        } else {
            ctx.bind_framebuffer(targets(out));
            prog_->use();
            ctx.draw_fullscreen();
        }
    }
    std::vector<std::string> targets(const std::string& out) const {
        if (out == "final" && write_ao_) return {out, "ao_smooth"};
        return {out};
    }
    pathlet::ShaderProgram* prog_ = nullptr;
    bool write_ao_ = false;
    bool compute_ = false;
};

pathlet::PassTypeInfo bilateral_type() {
    return pathlet::PassTypeBuilder("bilateral",
                                    "depth/normal-aware smoothing of AO, multiplied into the colour; background "
                                    "pixels copied unchanged")
        .param_int("radius", 4, 0, 16, "filter half-width in pixels ((2r+1)^2 taps)", {.pixels = true})
        .param_float("sigma_spatial", 2.5, 0.1, 32.0, "spatial Gaussian sigma in pixels", {.pixels = true})
        .param_float("sigma_depth", 0.01, 1e-5, 1.0,
                     "depth Gaussian sigma in normalised linear depth (lines further apart do not mix)")
        .param_float("normal_power", 1.0, 0.0, 64.0, "weight max(n.n',0)^power; 0 ignores normals")
        .param_bool("enabled", true, "false: plain multiply, to see LineAO's raw noise")
        .param_bool("separable", true,
                    "filter rows then columns (2(2r+1) taps, ~4x cheaper); false: the full 2-D kernel")
        .input_texture("ao", "r16f", "LineAO term (1 = unoccluded)")
        .input_texture("normal_depth", "rgba16f", "view-space normal (xyz), normalised linear depth (w)")
        .input_texture("color", "any", "line colour (rgba8 from gbuffer); alpha 0 = background")
        .input_texture("depth", "depth24", "G-buffer depth; when connected, background pixels are skipped",
                       {.optional = true})
        .output_texture("final", "rgba8", "colour x smoothed AO")
        .output_texture("ao_smooth", "r16f", "the smoothed AO alone, 1 on background (bind it to get it)",
                        {.optional = true})
        .internal_texture("tmp", "r16f", "separable mode: the horizontally filtered AO")
        .compute_version()
        .make<Bilateral>();
}

}  // namespace

PATHLET_PLUGIN("bilateral", { sink->add(bilateral_type()); })
