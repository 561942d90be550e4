// mboit_moments: moment-based OIT (Münstermann, Krumpen, Klein, Peters, I3D 2018), the first of
// its two additive passes. The window's fragments, drawn through the line kit with blending only,
// add per pixel their absorbance -ln(1 - alpha) (b0, r32f) and its first four power moments of
// the warped depth z (absorbance x z^k, k = 1..4: rgba32f). From these mboit_accum reconstructs
// every fragment's transmittance; oit_composite takes b0 as the pixel's total. 20 bytes a pixel;
// with `moments` power6 or power8 the moments z^5..z^8 go to `moments_high` (16 more).
#include <pathlet/lines.hpp>
#include <pathlet/oit.hpp>
#include <pathlet/plugin.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace lines = pathlet::lines;

class MboitMoments : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        coverage_ = ctx.connected("coverage");
        const pathlet::oit::MomentForm& form = pathlet::oit::moment_form(ctx.params());
        high_ = form.needs_high();
        if (high_ && !ctx.connected("moments_high"))
            throw std::runtime_error("moment_form=" + ctx.params().s("moment_form") +
                                     " keeps more than 4 floats of moments: connect the output 'moments_high' (rgba32f) "
                                     "to mboit_accum's input of that name (graphs/variant2_mboit8.json does; "
                                     "variant2_mboit keeps 4: power4, trig2)");
        prog_ = &lines::program(ctx, {"mboit_moments.frag"}, lines::hooks(ctx), form.defines());
        drawer_.set_depth_func(GL_ALWAYS);  // every fragment counts; the depth only records coverage
        drawer_.set_blending(true);
    }

    void execute(pathlet::PassContext& ctx) override {
        // moments_high, where connected but not used (power4), is neither attached nor cleared.
        std::vector<std::string> targets = {"b0", "moments"};
        if (high_) targets.push_back("moments_high");
        ctx.bind_framebuffer(targets, coverage_ ? "coverage" : "");
        const float zero[4] = {0, 0, 0, 0}, far = 1.0f;
        for (int i = 0; i < int(targets.size()); ++i) glClearBufferfv(GL_COLOR, i, zero);
        if (coverage_) glClearBufferfv(GL_DEPTH, 0, &far);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);  // sums over the pixel's fragments, in any order
        prog_->use();
        drawer_.draw(ctx, *prog_);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    lines::Drawer drawer_;
    bool coverage_ = false, high_ = false;
};

pathlet::PassTypeInfo mboit_moments_type() {
    pathlet::PassTypeBuilder b("mboit_moments",
                               "moment-based OIT (Münstermann et al. 2018), pass 1 of 2: each pixel's total "
                               "absorbance and its power moments of the log-warped depth, by additive blending (20 "
                               "bytes a pixel with 4 moments)");
    lines::declare_params(b, {.color = "fade_opacity.frag"});
    pathlet::oit::declare_moment_form(b)
        .output_texture("b0", "r32f", "the pixel's total absorbance, sum of -ln(1 - alpha)")
        .output_texture("moments", "rgba32f", "sum of absorbance x z^k, k = 1..4 (z: log depth warped to [-1, 1]); "
                        "trig: x e^(i k phi), k = 1, 2 (phi: z as an angle, mboit_common.glsl)")
        .output_texture("moments_high", "rgba32f", "power6: sum of absorbance x (z^5, z^6) in xy; power8: x z^k, "
                        "k = 5..8; trig3, trig4: x e^(i k phi), k = 3 (xy), 4 (zw); not drawn with power4, trig2", {.optional = true})
        .output_texture("coverage", "depth24", "depth < 1 where any fragment landed (the wall and oit_composite skip "
                        "the rest)", {.optional = true});
    return b.make<MboitMoments>();
}

}  // namespace

PATHLET_PLUGIN("mboit_moments", { sink->add(mboit_moments_type()); })
