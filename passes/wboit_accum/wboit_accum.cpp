// wboit_accum: weighted blended OIT (McGuire & Bavoil, JCGT 2(2), 2013), the accumulation. The
// pathlets of the window are drawn through the line kit once, with blending only: per pixel the
// sum of premultiplied colour x weight and of opacity x weight (rgba32f, additive), and the
// revealage, the product of (1 - opacity) (r32f, multiplicative). No lists, no sort, no
// read-back; oit_composite turns the two into the picture. 20 bytes a pixel (float32: llvmpipe
// blends it faster than half floats, 548 against about 940 ms a frame with every line whole,
// and the published weights cannot overflow it).
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

#include <string>
#include <vector>

namespace {

namespace lines = pathlet::lines;

class WboitAccum : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        coverage_ = lines::Coverage(ctx);
        prog_ = &lines::program(ctx, {"wboit_accum.frag"}, lines::hooks(ctx), lines::core_ao_defines(ctx));
        drawer_.set_depth_func(GL_ALWAYS);  // every fragment counts; the depth only records coverage
        drawer_.set_blending(true);
    }

    void execute(pathlet::PassContext& ctx) override {
        ctx.bind_framebuffer({"accum", "revealage"}, coverage_.depth_pin());
        const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1};
        glClearBufferfv(GL_COLOR, 0, zero);
        glClearBufferfv(GL_COLOR, 1, one);
        coverage_.clear();
        glEnable(GL_BLEND);
        glBlendFunci(0, GL_ONE, GL_ONE);                  // sum of (c a w, a w)
        glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);  // product of (1 - a)
        prog_->use();
        drawer_.draw(ctx, *prog_);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    lines::Drawer drawer_;
    lines::Coverage coverage_;
};

pathlet::PassTypeInfo wboit_accum_type() {
    pathlet::PassTypeBuilder b("wboit_accum",
                               "weighted blended OIT (McGuire & Bavoil 2013), accumulation: the window's fragments "
                               "blended into weighted premultiplied colour and revealage, no lists (20 bytes a "
                               "pixel); oit_composite resolves them");
    lines::declare_params(b, {.color = "fade_opacity.frag"})
        .param_enum("weight", "exponential", {"exponential", "depth_cubed", "linevis"},
                    "weight w(d, a), d the view's linear depth over [near, far]: exponential = a max(1e-4, 3000 "
                    "exp(-falloff d)) (steeper than the published ones: the nearest layers dominate), depth_cubed = "
                    "a max(0.01, 3000 (1 - d)^3) (the paper's eq. 10), linevis = clamp((8a + 0.01)^3 1e8 (1 - 0.95 "
                    "d)^3, 0.01, 300) (LineVis's)")
        .param_float("falloff", 25.0, 0.0, 80.0,
                     "exponential weight: e-folds of the weight over the depth range [near, far]")
        .output_texture("accum", "rgba32f", "sum of premultiplied colour x weight (rgb) and opacity x weight (a)")
        .output_texture("revealage", "r32f", "product of (1 - opacity) over the pixel's fragments (1: none)")
        .output_texture("coverage", "depth24", "depth < 1 where any fragment landed (the wall and oit_composite skip "
                        "the rest)", {.optional = true});
    lines::declare_core_ao_inputs(b);
    return b.make<WboitAccum>();
}

}  // namespace

PATHLET_PLUGIN("wboit_accum", { sink->add(wboit_accum_type()); })
