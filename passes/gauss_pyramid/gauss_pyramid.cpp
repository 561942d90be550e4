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
        prog_ = &ctx.program({"fullscreen.vert", "gauss_pyramid.frag"});
    }

    void execute(pathlet::PassContext& ctx) override {
        const auto& p = ctx.params();
        pathlet::Texture pyr = ctx.texture("pyramid");
        const int levels = std::clamp(p.i("levels"), 1, pyr.mips);
        prog_->use();
        const GLuint input = ctx.texture("normal_depth").id;
        if (p.b("copy_level0")) {
            ctx.bind_framebuffer({"pyramid"}, "", 0);
            prog_->bind_texture("u_src", input);
            prog_->set("u_mode", 0);
            ctx.draw_fullscreen();
        }
        prog_->set("u_mode", p.e<Mode>("mode") == Mode::box ? 2 : 1);
        // Only the lines' screen rectangle can hold geometry: each level is cleared to
        // background and the filter runs inside the rectangle (same texels as a full pass).
        const glm::ivec4 rect = pathlet::lines::screen_rect(ctx, 2);
        const float background[4] = {0.0f, 0.0f, 0.0f, 1.0f};  // ND_BACKGROUND
        for (int level = 1; level < levels; ++level) {
            const glm::ivec2 size(std::max(pyr.width >> level, 1), std::max(pyr.height >> level, 1));
            glClearTexImage(pyr.id, level, GL_RGBA, GL_FLOAT, background);
            pathlet::lines::ScopedScissor clip(pathlet::lines::rect_at_level(rect, level, 2, size));
            // Level 1 reads the input itself; deeper levels read a view of exactly level-1, so
            // the level being written is never sampled and no texture parameter changes
            // (changing BASE/MAX_LEVEL made llvmpipe wait for the previous draw: ~10 ms a level).
            prog_->bind_texture("u_src", level == 1 ? input : level_view(pyr, level - 1));
            ctx.bind_framebuffer({"pyramid"}, "", level);
            ctx.draw_fullscreen();
        }
        ctx.stat("levels built", levels);
    }

    ~GaussPyramid() override {
        for (auto& [key, view] : views_) glDeleteTextures(1, &view);
    }

private:
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
        .make<GaussPyramid>();
}

}  // namespace

PATHLET_PLUGIN("gauss_pyramid", { sink->add(gauss_pyramid_type()); })
