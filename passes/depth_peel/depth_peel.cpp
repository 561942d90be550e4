// depth_peel: exact transparency by depth peeling (Everitt 2001), the second exact technique
// beside the lists' resolve_exact, so each checks the other. Per layer the lines are drawn twice
// through the line kit: the peel finds, per pixel, the nearest depth behind the last layer
// peeled; the gather sums every fragment at exactly that depth into the layer (one depth, one
// layer: shaders/oit_depth_group.glsl, the rule resolve_exact follows); a fullscreen composite
// puts the layer under what is there (front to back). A pixel stops taking layers once its
// transmittance is below min_transmittance, and the peeling stops when a layer is empty: an
// occlusion query per layer, read back at once (the pass waits for the GPU every layer: a
// reference, not a frame loop). More than max_layers layers is an error naming the parameter,
// never a silent cut.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <stdexcept>
#include <string>

namespace {

namespace lines = pathlet::lines;

enum Phase { kCoverage = 0, kPeel = 1, kGather = 2 };

class DepthPeel : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        lines_ = &lines::program(ctx, {"depth_peel.frag"}, lines::hooks(ctx));
        composite_ = &ctx.program({"fullscreen.vert", "depth_peel_composite.frag"});
        drawer_.set_occlusion_culling(false);  // its depth buffers hold peels, not what hides what
        if (!query_) glCreateQueries(GL_ANY_SAMPLES_PASSED, 1, &query_);
    }

    ~DepthPeel() override {
        if (query_) glDeleteQueries(1, &query_);
    }

    void execute(pathlet::PassContext& ctx) override {
        const pathlet::Params& p = ctx.params();
        const glm::vec4 none(ctx.params().v3("background"), 0.0f), start(0.0f, 0.0f, 0.0f, 1.0f);
        const float none_peeled = -1.0f;  // in front of every fragment (depths are >= 0)
        // The last frame's composites wrote accum and peeled as images: their stores land
        // before these clears only behind a texture-update barrier.
        glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
        glClearTexImage(ctx.texture("color").id, 0, GL_RGBA, GL_FLOAT, &none.x);
        glClearTexImage(ctx.texture("accum").id, 0, GL_RGBA, GL_FLOAT, &start.x);
        glClearTexImage(ctx.texture("peeled").id, 0, GL_RED, GL_FLOAT, &none_peeled);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        if (ctx.connected("coverage")) {  // where visible fragments are, as fill_list's coverage
            ctx.bind_framebuffer({}, "coverage");
            lines::clear_depth(1.0f);
            draw_lines(ctx, kCoverage);
        }
        const glm::ivec4 rect = lines::screen_rect(ctx, 2);
        const int max_layers = p.i("max_layers");
        int layers = 0;
        for (;; ++layers) {
            ctx.bind_framebuffer({}, "peel_depth");
            lines::clear_depth(1.0f);
            glBeginQuery(GL_ANY_SAMPLES_PASSED, query_);
            draw_lines(ctx, kPeel);
            glEndQuery(GL_ANY_SAMPLES_PASSED);
            GLuint any = 0;
            glGetQueryObjectuiv(query_, GL_QUERY_RESULT, &any);  // waits: the peeling's only read-back
            if (!any) break;
            if (layers == max_layers)
                throw std::runtime_error("more than max_layers = " + std::to_string(max_layers) +
                                         " layers to peel (pixels still let light through); raise max_layers or "
                                         "min_transmittance");
            ctx.bind_framebuffer({"layer"}, "");
            lines::clear_color(0, glm::vec4(0.0f));
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE);  // the layer: sums over its fragments, in any order
            draw_lines(ctx, kGather);
            glDisable(GL_BLEND);
            ctx.bind_framebuffer({"color"}, "");
            composite_->use();
            {
                lines::ScopedScissor clip(rect);
                ctx.draw_fullscreen();
            }
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        }
        ctx.stat("layers", double(layers));
    }

private:
    void draw_lines(pathlet::PassContext& ctx, Phase phase) {
        // The coverage keeps the last visible fragment's depth, as fill_list's does (ALWAYS); the
        // peel the nearest (LEQUAL: a fragment clamped to 1.0 passes the cleared 1.0); the
        // gather has no depth target.
        drawer_.set_depth_func(phase == kPeel ? GL_LEQUAL : GL_ALWAYS);
        drawer_.set_blending(phase == kGather);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        lines_->use();
        lines_->set("u_phase", int(phase));
        drawer_.draw(ctx, *lines_);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    }

    pathlet::ShaderProgram* lines_ = nullptr;
    pathlet::ShaderProgram* composite_ = nullptr;
    lines::Drawer drawer_;
    GLuint query_ = 0;
};

pathlet::PassTypeInfo depth_peel_type() {
    pathlet::PassTypeBuilder b("depth_peel",
                               "exact transparency by depth peeling: layer by layer, a layer every fragment at one "
                               "depth (as resolve_exact composites them), until a layer is empty or every pixel's "
                               "transmittance is below min_transmittance; the colour hook's opacity (by default the "
                               "kit's end fade)");
    lines::declare_params(b, {.color = "fade_opacity.frag"})
        .param_int("max_layers", 4096, 1, 1000000,
                   "most layers peeled in a frame; a frame that needs more fails, naming this (never a silent cut)")
        .param_float("min_transmittance", 1e-4, 0.0, 1.0,
                     "a pixel whose light left through its layers is below this takes no more layers (as "
                     "resolve_exact stops)")
        .output_texture("color", "rgba8", "composited colour over `background`, alpha 1 where any fragment landed")
        .output_texture("coverage", "depth24",
                        "depth < 1 where a visible fragment landed (for the wall): fill_list's coverage, the same "
                        "fragments in the same order with depth test ALWAYS",
                        {.optional = true})
        .internal_texture("peel_depth", "depth32f", "this layer's linear depth per pixel (the peel draw's depth)")
        .internal_texture("layer", "rgba32f", "this layer's fragments summed: absorbance-weighted colour (rgb) and "
                                              "absorbance (a), shaders/oit_depth_group.glsl")
        .internal_texture("accum", "rgba32f", "colour composited so far (premultiplied) and the transmittance left")
        .internal_texture("peeled", "r32f", "the depth of the last layer peeled per pixel (-1: none yet)")
        .waits_for_gpu("an exact reference: after each layer it reads the layer's occlusion query, to stop at the "
                       "first empty layer");
    return b.make<DepthPeel>();
}

}  // namespace

PATHLET_PLUGIN("depth_peel", { sink->add(depth_peel_type()); })
