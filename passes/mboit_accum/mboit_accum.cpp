// mboit_accum: moment-based OIT (Münstermann et al. 2018), the second additive pass. The window's
// fragments are drawn again through the line kit; each reconstructs the transmittance in front of
// it from its pixel's moments (mboit_math.glsl) and adds its premultiplied colour times that
// transmittance, and its opacity times it, into an rgba16f target (8 bytes a pixel). oit_composite
// divides the two and puts the result over the background with exp(-b0). No order, no lists, no
// sync: blending only, as every GL 4.5 driver has it.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

#include <string>
#include <vector>

namespace {

namespace lines = pathlet::lines;

// The paper's moment bias for 4 float32 power moments (its table; as LineVis).
constexpr float kPaperBias = 5e-7f;

class MboitAccum : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        prog_ = &lines::program(ctx, {"mboit_accum.frag"}, lines::hooks(ctx), lines::core_ao_defines(ctx));
        drawer_.set_depth_func(GL_ALWAYS);
        drawer_.set_blending(true);
    }

    void execute(pathlet::PassContext& ctx) override {
        ctx.bind_framebuffer({"accum"});
        const float zero[4] = {0, 0, 0, 0};
        glClearBufferfv(GL_COLOR, 0, zero);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        prog_->use();
        const float bias = ctx.params().f("moment_bias");
        prog_->set("u_bias", bias < 0.0f ? kPaperBias : bias);
        drawer_.draw(ctx, *prog_);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    lines::Drawer drawer_;
};

pathlet::PassTypeInfo mboit_accum_type() {
    pathlet::PassTypeBuilder b("mboit_accum",
                               "moment-based OIT (Münstermann et al. 2018), pass 2 of 2: each fragment's colour "
                               "times the transmittance reconstructed from its pixel's moments, by additive blending "
                               "(8 bytes a pixel); oit_composite resolves it");
    lines::declare_params(b, {.color = "fade_opacity.frag"})
        .param_float("overestimation", 0.1, 0.0, 1.0,
                     "beta: the share of a fragment's own absorbance counted in front of it (the paper's 0.1; 0 "
                     "underestimates occlusion, 1 overestimates it)")
        .param_float("moment_bias", -1.0, -1.0, 0.5,
                     "how far the normalised moments are moved towards the uniform distribution's before the "
                     "reconstruction; < 0: the paper's value for 4 float32 moments, 5e-7")
        .input_texture("b0", "r32f", "the total absorbance (mboit_moments)")
        .input_texture("moments", "rgba32f", "moments 1..4 (mboit_moments)")
        .output_texture("accum", "rgba16f", "sum of premultiplied colour x transmittance (rgb) and alpha x "
                        "transmittance (a)");
    lines::declare_core_ao_inputs(b);
    return b.make<MboitAccum>();
}

}  // namespace

PATHLET_PLUGIN("mboit_accum", { sink->add(mboit_accum_type()); })
