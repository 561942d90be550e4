// gauss_pyramid: normal/depth pyramid for LineAO's per-level sampling (seed eq. 6: level l
// samples the l-th level). Level 0 copies the input; every further level is a 2x downsample
// with a binomial (Gaussian) kernel that ignores background, or OpenWalnut's box mips.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <algorithm>
#include <map>
#include <utility>

namespace {

enum class Mode { gaussian, box };  // the choices of `mode`

class GaussPyramid : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        compute_ = ctx.use_compute();
        prog_ = &ctx.fullscreen_program("gauss_pyramid.frag");
    }

    void execute(pathlet::PassContext& ctx) override {
        const auto& p = ctx.params();
        ctx.stat(pathlet::kComputeStat, compute_ ? 1.0 : 0.0);
        pathlet::Texture pyr = ctx.texture("pyramid");
        const int levels = std::clamp(p.i("levels"), 1, pyr.mips);
        prog_->use();
        const GLuint input = ctx.texture("normal_depth").id;
        if (p.b("copy_level0")) {
            prog_->bind_texture("u_src", input);
            prog_->set("u_mode", 0);
            run_level(ctx, pyr, 0, glm::ivec4(0, 0, pyr.width, pyr.height));
        }
        prog_->set("u_mode", p.e<Mode>("mode") == Mode::box ? 2 : 1);
        // Only the lines' screen rectangle can hold geometry: each level is cleared to
        // background and the filter runs inside the rectangle (same texels as a full pass).
        const glm::ivec4 rect = pathlet::lines::screen_rect(ctx, 2);
        const float background[4] = {0.0f, 0.0f, 0.0f, 1.0f};  // ND_BACKGROUND
        for (int level = 1; level < levels; ++level) {
            const glm::ivec2 size(std::max(pyr.width >> level, 1), std::max(pyr.height >> level, 1));
            glClearTexImage(pyr.id, level, GL_RGBA, GL_FLOAT, background);
            // Level 1 reads the input itself; deeper levels read a view of exactly level-1, so
            // the level being written is never sampled and no texture parameter changes
            // (changing BASE/MAX_LEVEL made llvmpipe wait for the previous draw: ~10 ms a level).
            prog_->bind_texture("u_src", level == 1 ? input : level_view(pyr, level - 1));
            run_level(ctx, pyr, level, pathlet::lines::rect_at_level(rect, level, 2, size));
        }
        ctx.stat("levels built", levels);
    }

    ~GaussPyramid() override {
        for (auto& [key, view] : views_) glDeleteTextures(1, &view);
    }

private:
    // Writes mip `level` of the pyramid inside `rect` (that level's pixels): drawn, or dispatched
    // with the level bound as the image u_pyramid (the dispatch's barrier lets the next level read it).
    void run_level(pathlet::PassContext& ctx, const pathlet::Texture& pyr, int level, glm::ivec4 rect) {
        if (compute_) {
            prog_->bind_image("u_pyramid", pyr.id, pyr.internal_format, GL_WRITE_ONLY, level);
            ctx.dispatch_fullscreen(*prog_, rect);
            return;
        }
        pathlet::lines::ScopedScissor clip(rect);
        ctx.bind_framebuffer({"pyramid"}, "", level);
        prog_->use();
        ctx.draw_fullscreen();
    }

    // A one-level texture view of `tex` (immutable storage), made once and reused.
    GLuint level_view(const pathlet::Texture& tex, int level) {
        GLuint& v = views_[{tex.id, level}];
        if (!v) {
            glGenTextures(1, &v);  // views need a name that was never bound
            glTextureView(v, GL_TEXTURE_2D, tex.id, tex.internal_format, GLuint(level), 1, 0, 1);
            glTextureParameteri(v, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(v, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
        return v;
    }
    std::map<std::pair<GLuint, int>, GLuint> views_;
    pathlet::ShaderProgram* prog_ = nullptr;
    bool compute_ = false;
};

pathlet::PassTypeInfo gauss_pyramid_type() {
    return pathlet::PassTypeBuilder(
               "gauss_pyramid",
               "normal/depth pyramid for LineAO: level 0 = input, each next level a background-aware "
               "binomial (Gaussian) 2x downsample, or plain box mips")
        .param_enum("mode", "gaussian", {"gaussian", "box"},
                    "gaussian: [1 3 3 1]^2 binomial downsample that skips background texels and renormalises "
                    "normals; box: plain 2x2 average like glGenerateMipmap (OpenWalnut), background included")
        .param_int("levels", 4, 1, 16,
                   "levels written, level 0 included (the rest stay untouched); keep >= lineao's radii")
        .param_bool("copy_level0", true,
                    "write level 0 (a copy of the input); lineao reads level 0 from normal_depth itself, so "
                    "graphs feeding only lineao may turn this off and save one full-screen rgba16f write")
        .input_texture("normal_depth", "rgba16f", "view-space normal (xyz) and normalised linear depth (w)")
        .output_texture("pyramid", "rgba16f", "the pyramid; mip l = level l", {.mips = 0 /* full chain */})
        .compute_version()
        .make<GaussPyramid>();
}

}  // namespace

PATHLET_PLUGIN("gauss_pyramid", { sink->add(gauss_pyramid_type()); })
