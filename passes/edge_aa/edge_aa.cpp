// edge_aa: anti-aliasing that fits a deferred LineAO pipeline. The line kit's G-buffer records
// each pixel's nearer rim in pixels (the optional `edge` output); after lighting, AO and the
// wall, this pass blends across those rims by the analytic coverage (edge_aa.frag). One
// full-screen pass of five fetches, no extra samples: the AO stays computed once per pixel.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

namespace {

enum class Alpha { opaque, coverage };  // the choices of `alpha`

class EdgeAA : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        compute_ = ctx.use_compute();
        prog_ = &ctx.fullscreen_program("edge_aa.frag");
    }

    void execute(pathlet::PassContext& ctx) override {
        const pathlet::Params& p = ctx.params();
        ctx.stat(pathlet::kComputeStat, compute_ ? 1.0 : 0.0);
        const bool opaque = p.e<Alpha>("alpha") == Alpha::opaque;
        pathlet::Texture src = ctx.texture("color"), dst = ctx.texture("final");
        if (!p.b("enabled") && !opaque) {  // pass through bit for bit
            glCopyImageSubData(src.id, GL_TEXTURE_2D, 0, 0, 0, 0, dst.id, GL_TEXTURE_2D, 0, 0, 0, 0, dst.width,
                               dst.height, 1);
            return;
        }
        // Lines can only be inside their screen rectangle: outside it the image is copied (and
        // flattened: alpha set to 1, the colour is the background's already). The shader runs on
        // the rectangle only.
        const glm::ivec4 r = pathlet::lines::screen_rect(ctx, 2);
        prog_->use();  // u_alpha, u_enabled and the samplers by declaration
        ctx.bind_framebuffer({"final"});
        glCopyImageSubData(src.id, GL_TEXTURE_2D, 0, 0, 0, 0, dst.id, GL_TEXTURE_2D, 0, 0, 0, 0, dst.width,
                           dst.height, 1);
        if (opaque) {
            const float one[4] = {0.0f, 0.0f, 0.0f, 1.0f};
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
            glClearBufferfv(GL_COLOR, 0, one);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        }
        if (compute_) {
            ctx.dispatch_fullscreen(*prog_, r);
            return;
        }
        pathlet::lines::ScopedScissor clip(r);
        ctx.draw_fullscreen();
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    bool compute_ = false;
};

}  // namespace

PATHLET_PLUGIN("edge_aa", {
    sink->add(pathlet::PassTypeBuilder("edge_aa",
                                       "anti-aliased line edges from the G-buffer's analytic rim distance, after "
                                       "lighting (smooth against the background, the wall and lines behind)")
                  .param_bool("enabled", true, "blend across the rims (false: the image as it is, only flattened "
                                               "when alpha = opaque)")
                  .param_enum("alpha", "opaque", {"opaque", "coverage"},
                              "opaque: every pixel over the background colour, alpha 1 (video frames); coverage: "
                              "the background stays transparent and edge pixels get their coverage as alpha")
                  .input_texture("color", "rgba8", "the finished image: lines lit, wall behind")
                  .input_texture("edge", "rgba8", "the line pass's `edge` output (rim direction and distance)")
                  .input_texture("depth", "depth24", "the line pass's z-buffer: which line is in front")
                  .output_texture("final", "rgba8", "the anti-aliased image")
                  .compute_version()
                  .make<EdgeAA>());
})
