// mboit_accum: moment-based OIT (Münstermann et al. 2018), the second additive pass. The window's
// fragments are drawn again through the line kit; each reconstructs the transmittance in front of
// it from its pixel's moments (mboit_math.glsl) and adds its premultiplied colour times that
// transmittance, and its opacity times it, into an rgba16f target (8 bytes a pixel). oit_composite
// divides the two and puts the result over the background with exp(-b0). No order, no lists, no
// sync: blending only, as every GL 4.5 driver has it.
#include <pathlet/lines.hpp>
#include <pathlet/oit.hpp>
#include <pathlet/plugin.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace lines = pathlet::lines;

class MboitAccum : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        form_ = &pathlet::oit::moment_form(ctx.params());
        // The form is the writer's too (the graph compiler checks); the high moments must then be
        // wired (with power4 a connected moments_high is left unread).
        if (form_->needs_high() && !ctx.connected("moments_high"))
            throw std::runtime_error("moment_form=" + ctx.params().s("moment_form") +
                                     " reads 'moments_high' (more than 4 floats): connect it to mboit_moments' output of that "
                                     "name, with the same moment_form there (graphs/variant2_mboit8.json does)");
        std::vector<std::string> defines = lines::core_ao_defines(ctx);
        for (const std::string& d : form_->defines()) defines.push_back(d);
        prog_ = &lines::program(ctx, {"mboit_accum.frag"}, lines::hooks(ctx), defines);
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
        prog_->set("u_bias", bias < 0.0f ? form_->default_bias : bias);
        drawer_.draw(ctx, *prog_);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    lines::Drawer drawer_;
    const pathlet::oit::MomentForm* form_ = nullptr;
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
                     "reconstruction; < 0: 5e-7 for the power forms (the paper's for 4 float32 moments; for 6 and 8 "
                     "it gives 5e-6 and 5e-5, which this reconstruction does not need: README), the paper's 4e-7, "
                     "8e-7, 1.5e-6 for trig2..trig4");
    // mboit_moments must have drawn the same fragments with the same form: every parameter the
    // two passes share is checked when the graph compiles.
    pathlet::oit::declare_moment_form(b)
        .input_texture("b0", "r32f", "the total absorbance (mboit_moments)", {.same_params = {"*"}})
        .input_texture("moments", "rgba32f", "moments 1..4 (mboit_moments)", {.same_params = {"*"}})
        .input_texture("moments_high", "rgba32f", "moments 5..8 (mboit_moments' with power6, power8)",
                       {.optional = true, .same_params = {"*"}})
        .output_texture("accum", "rgba16f", "sum of premultiplied colour x transmittance (rgb) and alpha x "
                        "transmittance (a)");
    lines::declare_core_ao_inputs(b);
    return b.make<MboitAccum>();
}

}  // namespace

PATHLET_PLUGIN("mboit_accum", { sink->add(mboit_accum_type()); })
