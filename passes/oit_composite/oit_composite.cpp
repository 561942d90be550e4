// oit_composite: the resolve of the blend-only OIT techniques (wboit_accum, mboit_accum). Both
// leave per pixel a weighted sum of premultiplied colour (rgb) and of the weights (a), and the
// pixel's total transmittance: WBOIT as its revealage (the product of 1 - alpha), MBOIT as the
// total absorbance b0 (transmittance exp(-b0)). The picture is the weighted mean colour over
// (1 - transmittance) of the pixel, the background through the rest (McGuire & Bavoil 2013,
// eq. 6; Münstermann et al. 2018, sec. 3.3), alpha 1 wherever a fragment landed, as
// resolve_list gives it.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace {

class OitComposite : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        const bool rev = ctx.connected("revealage"), absorb = ctx.connected("absorbance");
        if (rev == absorb)
            throw std::runtime_error("connect exactly one of 'revealage' (wboit_accum) and 'absorbance' (mboit_moments' "
                                     "b0)");
        prog_ = &ctx.program({"fullscreen.vert", "oit_composite.frag"},
                             {rev ? "TRANSMITTANCE_FROM_REVEALAGE" : "TRANSMITTANCE_FROM_ABSORBANCE"});
    }

    void execute(pathlet::PassContext& ctx) override {
        const pathlet::lines::Coverage coverage(ctx);
        if (coverage.connected()) {  // the background everywhere first; the shader then runs on covered tiles only
            const glm::vec4 bg(ctx.params().v3("background"), 0.0f);
            glClearTexImage(ctx.texture("color").id, 0, GL_RGBA, GL_FLOAT, &bg.x);
        }
        ctx.bind_framebuffer({"color"}, coverage.depth_pin());
        coverage.draw(ctx, *prog_);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
};

pathlet::PassTypeInfo oit_composite_type() {
    return pathlet::PassTypeBuilder("oit_composite",
                                    "resolve of blend-only OIT (wboit_accum, mboit_accum): the weighted mean colour "
                                    "over 1 - the pixel's transmittance, the background through the rest")
        .param_color("background", {1.0f, 1.0f, 1.0f}, "colour behind all fragments")
        .input_texture("accum", "any", "weighted premultiplied colour (rgb) and the weights' sum (a)")
        .input_texture("revealage", "any", "WBOIT: the product of (1 - alpha) (wboit_accum); or absorbance",
                       {.optional = true})
        .input_texture("absorbance", "r32f", "MBOIT: the total absorbance b0 (mboit_moments); or revealage",
                       {.optional = true})
        .input_texture("coverage", "depth24",
                       "depth < 1 where any fragment landed: when connected, the other pixels are only cleared",
                       {.optional = true})
        .output_texture("color", "rgba8", "composited colour, alpha 1 where any fragment landed")
        .make<OitComposite>();
}

}  // namespace

PATHLET_PLUGIN("oit_composite", { sink->add(oit_composite_type()); })
