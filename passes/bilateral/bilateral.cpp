// bilateral: removes LineAO's fixed noise pattern with a cross-bilateral filter guided by
// depth and normals (so AO does not leak between lines at different depths), then
// multiplies AO into the colour. Background pixels pass through untouched.
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <algorithm>

namespace {

class Bilateral : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override { prog_ = &ctx.program({"fullscreen.vert", "bilateral.frag"}); }

    void execute(pathlet::PassContext& ctx) override {
        const auto& p = ctx.params();
        const float ss = std::max(p.f("sigma_spatial"), 1e-3f);
        prog_->use();
        prog_->set("u_radius", p.i("radius"));
        prog_->set("u_inv2_sigma_s2", 1.0f / (2.0f * ss * ss));
        prog_->set("u_inv_sigma_d", 1.0f / std::max(p.f("sigma_depth"), 1e-6f));
        prog_->set("u_normal_power", p.f("normal_power"));
        prog_->set("u_enabled", p.b("enabled") ? 1 : 0);
        glBindTextureUnit(0, ctx.texture("ao").id);
        glBindTextureUnit(1, ctx.texture("normal_depth").id);
        glBindTextureUnit(2, ctx.texture("color").id);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        ctx.bind_framebuffer({"final"});
        ctx.draw_fullscreen();
        for (GLuint unit : {0u, 1u, 2u}) glBindTextureUnit(unit, 0);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
};

pathlet::PassTypeInfo bilateral_type() {
    return pathlet::PassTypeBuilder("bilateral",
                                    "depth/normal-aware smoothing of AO, multiplied into the colour; background "
                                    "pixels copied unchanged")
        .param_int("radius", 4, 0, 16, "filter half-width in pixels ((2r+1)^2 taps)")
        .param_float("sigma_spatial", 2.5, 0.1, 32.0, "spatial Gaussian sigma in pixels")
        .param_float("sigma_depth", 0.01, 1e-5, 1.0,
                     "depth Gaussian sigma in normalised linear depth (lines further apart do not mix)")
        .param_float("normal_power", 1.0, 0.0, 64.0, "weight max(n.n',0)^power; 0 ignores normals")
        .param_bool("enabled", true, "false: plain multiply, to see LineAO's raw noise")
        .input_texture("ao", "r16f", "LineAO term (1 = unoccluded)")
        .input_texture("normal_depth", "rgba16f", "view-space normal (xyz), normalised linear depth (w)")
        .input_texture("color", "any", "line colour (rgba8 from gbuffer); alpha 0 = background")
        .output_texture("final", "rgba8", "colour x smoothed AO")
        .make<Bilateral>();
}

}  // namespace

PATHLET_PLUGIN("bilateral", { sink->add(bilateral_type()); })
