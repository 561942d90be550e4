// mboit_moments: moment-based OIT (Münstermann, Krumpen, Klein, Peters, I3D 2018), the first of
// its two additive passes. The window's fragments, drawn through the line kit with blending only,
// add per pixel their absorbance -ln(1 - alpha) (b0, r32f) and its first four power moments of
// the warped depth z (absorbance x z^k, k = 1..4: rgba32f). From these mboit_accum reconstructs
// every fragment's transmittance; oit_composite takes b0 as the pixel's total. 20 bytes a pixel.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

#include <string>
#include <vector>

namespace {

namespace lines = pathlet::lines;

class MboitMoments : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        coverage_ = ctx.connected("coverage");
        prog_ = &lines::program(ctx, {"mboit_moments.frag"}, lines::hooks(ctx));
        drawer_.set_depth_func(GL_ALWAYS);  // every fragment counts; the depth only records coverage
        drawer_.set_blending(true);
    }

    void execute(pathlet::PassContext& ctx) override {
        ctx.bind_framebuffer({"b0", "moments"}, coverage_ ? "coverage" : "");
        const float zero[4] = {0, 0, 0, 0}, far = 1.0f;
        glClearBufferfv(GL_COLOR, 0, zero);
        glClearBufferfv(GL_COLOR, 1, zero);
        if (coverage_) glClearBufferfv(GL_DEPTH, 0, &far);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);  // sums over the pixel's fragments, in any order
        prog_->use();
        drawer_.draw(ctx, *prog_);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    lines::Drawer drawer_;
    bool coverage_ = false;
};

pathlet::PassTypeInfo mboit_moments_type() {
    pathlet::PassTypeBuilder b("mboit_moments",
                               "moment-based OIT (Münstermann et al. 2018), pass 1 of 2: each pixel's total "
                               "absorbance and its power moments of the log-warped depth, by additive blending (20 "
                               "bytes a pixel with 4 moments)");
    lines::declare_params(b, {.color = "fade_opacity.frag"})
        .output_texture("b0", "r32f", "the pixel's total absorbance, sum of -ln(1 - alpha)")
        .output_texture("moments", "rgba32f", "sum of absorbance x z^k, k = 1..4 (z: log depth warped to [-1, 1])")
        .output_texture("coverage", "depth24", "depth < 1 where any fragment landed (the wall and oit_composite skip "
                        "the rest)", {.optional = true});
    return b.make<MboitMoments>();
}

}  // namespace

PATHLET_PLUGIN("mboit_moments", { sink->add(mboit_moments_type()); })
