// mlab_bucket: the depth-bucket pre-pass of MLAB with depth buckets (Kern et al., "A Comparison of
// Rendering Techniques for 3D Line Sets with Transparency", IEEE TVCG 27(8), 2021). The window's
// fragments are drawn through the line kit with MIN blending only: per pixel the nearest depth of
// a fragment more opaque than lower_opacity (where mlab_blend's layers begin: fainter fragments
// in front of it share one front bucket) and the nearest of one at least upper_opacity opaque
// (what lies behind it is hidden: mlab_blend drops it). 8 bytes a pixel; no sync needed.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

namespace {

namespace lines = pathlet::lines;

class MlabBucket : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        coverage_ = ctx.connected("coverage");
        prog_ = &lines::program(ctx, {"mlab_bucket.frag"}, lines::hooks(ctx));
        drawer_.set_depth_func(GL_ALWAYS);  // every fragment counts; the depth only records coverage
        drawer_.set_blending(true);
    }

    void execute(pathlet::PassContext& ctx) override {
        ctx.bind_framebuffer({"bucket"}, coverage_ ? "coverage" : "");
        const float far[4] = {1, 1, 1, 1}, depth = 1.0f;
        glClearBufferfv(GL_COLOR, 0, far);
        if (coverage_) glClearBufferfv(GL_DEPTH, 0, &depth);
        glEnable(GL_BLEND);
        glBlendEquation(GL_MIN);  // the nearest, in any order
        glBlendFunc(GL_ONE, GL_ONE);
        prog_->use();
        drawer_.draw(ctx, *prog_);
        glBlendEquation(GL_FUNC_ADD);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    lines::Drawer drawer_;
    bool coverage_ = false;
};

pathlet::PassTypeInfo mlab_bucket_type() {
    pathlet::PassTypeBuilder b("mlab_bucket",
                               "MLAB with depth buckets (Kern et al. 2021), pre-pass: per pixel the nearest depth of a "
                               "fragment above lower_opacity and of one at least upper_opacity opaque, by MIN blending "
                               "(8 bytes a pixel)");
    lines::declare_params(b, {.color = "fade_opacity.frag"})
        .param_float("lower_opacity", 0.2, 0.0, 1.0,
                     "fragments more opaque than this start mlab_blend's layers; fainter ones in front of the first "
                     "share the front bucket (Kern et al.: 0.2)",
                     {.at_most = "upper_opacity"})
        .param_float("upper_opacity", 0.98, 0.0, 1.0,
                     "a fragment at least this opaque hides what lies behind it (Kern et al.: 0.98; 0.06 for UCLA)")
        .output_texture("bucket", "rg32f", "nearest depth above lower_opacity (r) and at or above upper_opacity (g); "
                        "1 where none")
        .output_texture("coverage", "depth24", "depth < 1 where any fragment landed", {.optional = true});
    return b.make<MlabBucket>();
}

}  // namespace

PATHLET_PLUGIN("mlab_bucket", { sink->add(mlab_bucket_type()); })
