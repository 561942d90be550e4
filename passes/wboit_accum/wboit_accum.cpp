// wboit_accum: weighted blended OIT (McGuire & Bavoil, JCGT 2(2), 2013), the accumulation. The
// pathlets of the window are drawn through the line kit once, with blending only: per pixel the
// sum of premultiplied colour x weight and of opacity x weight (rgba16f, additive), and the
// revealage, the product of (1 - opacity) (r16f, multiplicative). No lists, no sort, no
// read-back; oit_composite turns the two into the picture. 10 bytes a pixel.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

#include <string>
#include <vector>

namespace {

namespace lines = pathlet::lines;

class WboitAccum : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        coverage_ = ctx.connected("coverage");
        prog_ = &lines::program(ctx, {"wboit_accum.frag"}, lines::hooks(ctx), lines::core_ao_defines(ctx));
        drawer_.set_depth_func(GL_ALWAYS);  // every fragment counts; the depth only records coverage
        drawer_.set_blending(true);
    }

    void execute(pathlet::PassContext& ctx) override {
        ctx.bind_framebuffer({"accum", "revealage"}, coverage_ ? "coverage" : "");
        const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1}, far = 1.0f;
        glClearBufferfv(GL_COLOR, 0, zero);
        glClearBufferfv(GL_COLOR, 1, one);
        if (coverage_) glClearBufferfv(GL_DEPTH, 0, &far);
        glEnable(GL_BLEND);
        glBlendFunci(0, GL_ONE, GL_ONE);                  // sum of (c a w, a w)
        glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);  // product of (1 - a)
        prog_->use();
        drawer_.draw(ctx, *prog_);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    lines::Drawer drawer_;
    bool coverage_ = false;
};

pathlet::PassTypeInfo wboit_accum_type() {
    pathlet::PassTypeBuilder b("wboit_accum",
                               "weighted blended OIT (McGuire & Bavoil 2013), accumulation: the window's fragments "
                               "blended into weighted premultiplied colour and revealage, no lists (10 bytes a "
                               "pixel); oit_composite resolves them");
    lines::declare_params(b, {.color = "fade_opacity.frag"})
        .param_enum("weight", "depth_cubed", {"depth_cubed", "linevis"},
                    "weight w(d, a), d the view's linear depth over [near, far]: depth_cubed = a max(1e-4, 30 (1 - "
                    "d)^3) (the paper's eq. 10 / 100), linevis = clamp((8a + 0.01)^3 1e6 (1 - 0.95 d)^3, 1e-4, 3) "
                    "(LineVis's weight / 100); a common factor leaves the picture as it is and keeps rgba16f finite")
        .output_texture("accum", "rgba16f", "sum of premultiplied colour x weight (rgb) and opacity x weight (a)")
        .output_texture("revealage", "r16f", "product of (1 - opacity) over the pixel's fragments (1: none)")
        .output_texture("coverage", "depth24", "depth < 1 where any fragment landed (the wall and oit_composite skip "
                        "the rest)", {.optional = true});
    lines::declare_core_ao_inputs(b);
    return b.make<WboitAccum>();
}

}  // namespace

PATHLET_PLUGIN("wboit_accum", { sink->add(wboit_accum_type()); })
