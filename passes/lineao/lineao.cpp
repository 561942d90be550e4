// lineao: the LineAO term per pixel (shared/LINEAO.md). The per-level constants (sample
// counts, radius growth, delta(l), the kernel's starting angle) are computed here when the
// parameters change and passed as uniforms, so the shader has uniform loop bounds and no
// recompiles; the kernel itself is generated in lineao.frag.
#include <pathlet/gpu_scene.hpp>
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

constexpr int kMaxLevels = 8;    // = MAX_LEVELS in lineao.frag

struct Levels {
    int count = 0;
    int samples[kMaxLevels] = {}, total = 0;
    float growth[kMaxLevels] = {}, delta[kMaxLevels] = {};
    glm::vec2 start[kMaxLevels] = {};  // (cos, sin) of the kernel's first angle
};

Levels make_levels(const pathlet::Params& p) {
    Levels L;
    L.count = std::clamp(p.i("radii"), 1, kMaxLevels);
    const int s_h = std::max(1, p.i("samples"));
    const bool running_sum = p.s("radius_growth") == "running_sum";
    const float delta0 = p.f("delta0");
    for (int l = 0; l < L.count; ++l) {
        const float fl = float(l), sr = float(L.count);
        L.samples[l] = std::max(1, s_h / (l + 1));  // seed eq. 6
        L.total += L.samples[l];
        // Growth in line widths beyond r0. linear: paper, r0 + l*z(P). running_sum: the
        // authors' 1.5, 4, 7.5, 12 ... shifted so level 0 is r0 too (0, 2.5, 6, 10.5 ...).
        L.growth[l] = running_sum ? 0.5f * fl * (fl + 4.0f) : fl;
        // delta(l) = (1 - l/s_r)^2 * density weight (paper; the code's s_r - 1 breaks at the
        // last level), guarded above delta0 so smoothstep's edges stay ordered.
        const float d = (1.0f - fl / sr) * (1.0f - fl / sr) * p.f("density_weight");
        L.delta[l] = std::max(d, delta0 + std::max(1e-6f, delta0 * 1e-3f));
        // The kernel, a Fibonacci hemisphere around +z (uniform in area) with a van der Corput
        // radial sequence, is generated in lineao.frag; each level starts at its own angle.
        L.start[l] = glm::vec2(std::cos(1.3f * fl), std::sin(1.3f * fl));
    }
    return L;
}

class LineAO : public pathlet::Pass {
public:
    // Everything that depends only on parameters and the scene is uploaded once here: the
    // program keeps its uniforms, and setup() runs again whenever a parameter changes.
    void setup(pathlet::PassContext& ctx) override {
        const auto& p = ctx.params();
        prog_ = &ctx.program({"fullscreen.vert", "lineao.frag"}, pathlet::whole_exponent("LINEAO_EXPONENT", p.f("exponent")));
        const Levels L = make_levels(p);
        pyramid_ = p.b("use_pyramid") && ctx.connected("pyramid");
        glm::vec3 light = p.v3("light_dir");
        light = glm::length(light) > 1e-6f ? glm::normalize(light) : glm::vec3(0, 0, 1);
        const GLuint id = prog_->id();
        prog_->set("u_levels", L.count);
        glProgramUniform1iv(id, prog_->loc("u_count"), L.count, L.samples);
        glProgramUniform1fv(id, prog_->loc("u_growth"), L.count, L.growth);
        glProgramUniform1fv(id, prog_->loc("u_delta"), L.count, L.delta);
        glProgramUniform2fv(id, prog_->loc("u_level_dir"), L.count, glm::value_ptr(L.start[0]));
        prog_->set("u_r0", p.f("r0") * ctx.pixel_scale());
        prog_->set("u_lod_offset", int(std::lround(std::log2(std::max(ctx.pixel_scale(), 1.0f)))));
        prog_->set("u_line_width", ctx.scene().line_width(p.f("line_width"), p.f("width_factor")));
        prog_->set("u_strength", p.f("strength"));
        prog_->set("u_delta0", p.f("delta0"));
        prog_->set("u_use_pyramid", pyramid_ ? 1 : 0);
        prog_->set("u_max_lod", pyramid_ ? ctx.texture("pyramid").mips - 1 : 0);
        prog_->set("u_occluder_light", p.b("occluder_light") ? 1 : 0);
        prog_->set("u_light", light);
        prog_->set("u_exponent", p.f("exponent"));
        prog_->set("u_spec_cut", std::pow(1e-4f, 1.0f / p.f("exponent")));
        glProgramUniform1ui(id, prog_->loc("u_seed"), uint32_t(p.i("seed")));
        samples_ = double(L.total);

        // Half resolution: the term for one pixel in four into a private texture, then a
        // depth-aware upsampling into `ao` (lineao_upsample.frag).
        half_ = p.s("resolution") == "half";
        prog_->set("u_half", half_ ? 1 : 0);
        if (half_) {
            const glm::ivec2 size = ctx.texture("ao").width > 0
                                        ? glm::ivec2(ctx.texture("ao").width, ctx.texture("ao").height)
                                        : ctx.output_size();
            const glm::ivec2 hs = (size + 1) / 2;
            if (hs != half_size_) {
                release_half();
                half_size_ = hs;
                glCreateTextures(GL_TEXTURE_2D, 1, &half_tex_);
                glTextureStorage2D(half_tex_, 1, GL_R16F, hs.x, hs.y);
                glCreateFramebuffers(1, &half_fbo_);
                glNamedFramebufferTexture(half_fbo_, GL_COLOR_ATTACHMENT0, half_tex_, 0);
            }
            upsample_ = &ctx.program({"fullscreen.vert", "lineao_upsample.frag"});
            upsample_->set("u_inv_sigma_d", 1.0f / 0.01f);
        }
    }

    ~LineAO() override { release_half(); }

    void execute(pathlet::PassContext& ctx) override {
        prog_->use();
        glBindTextureUnit(0, ctx.texture("normal_depth").id);
        glBindTextureUnit(2, ctx.texture("zoom").id);
        // Unit 1 is never read without the pyramid; binding normal_depth keeps it valid.
        glBindTextureUnit(1, ctx.texture(pyramid_ ? "pyramid" : "normal_depth").id);
        glDisable(GL_BLEND);
        // Covered pixels lie inside the lines' screen rectangle; outside it the term stays 1.
        const glm::ivec4 rect = pathlet::lines::screen_rect(ctx, 2);
        if (half_) {
            const float one = 1.0f;
            glClearTexImage(half_tex_, 0, GL_RED, GL_FLOAT, &one);
            glBindFramebuffer(GL_FRAMEBUFFER, half_fbo_);
            glViewport(0, 0, half_size_.x, half_size_.y);
            glDisable(GL_DEPTH_TEST);
            {
                pathlet::lines::ScopedScissor clip(pathlet::lines::rect_at_level(rect, 1, 1, half_size_));
                ctx.draw_fullscreen();  // background texels return 1 at once
            }
            glClearTexImage(ctx.texture("ao").id, 0, GL_RED, GL_FLOAT, &one);
            upsample_->use();
            glBindTextureUnit(1, half_tex_);
            pathlet::lines::ScopedScissor clip(rect);
            if (ctx.connected("depth")) {
                ctx.bind_framebuffer({"ao"}, "depth");
                ctx.draw_fullscreen_on_geometry(*upsample_);
            } else {
                ctx.bind_framebuffer({"ao"});
                ctx.draw_fullscreen();
            }
        } else if (ctx.connected("depth")) {
            // Background stays 1 (cleared); only covered pixels run the shader.
            const float one = 1.0f;
            glClearTexImage(ctx.texture("ao").id, 0, GL_RED, GL_FLOAT, &one);
            ctx.bind_framebuffer({"ao"}, "depth");
            pathlet::lines::ScopedScissor clip(rect);
            ctx.draw_fullscreen_on_geometry(*prog_);
        } else {
            glDisable(GL_DEPTH_TEST);
            ctx.bind_framebuffer({"ao"});
            ctx.draw_fullscreen();
        }
        for (GLuint unit : {0u, 1u, 2u}) glBindTextureUnit(unit, 0);
        ctx.stat("samples per pixel", samples_);
    }

private:
    void release_half() {
        if (half_fbo_) glDeleteFramebuffers(1, &half_fbo_);
        if (half_tex_) glDeleteTextures(1, &half_tex_);
        half_fbo_ = half_tex_ = 0;
        half_size_ = glm::ivec2(0);
    }

    pathlet::ShaderProgram* prog_ = nullptr;
    pathlet::ShaderProgram* upsample_ = nullptr;
    bool half_ = false;
    GLuint half_tex_ = 0, half_fbo_ = 0;
    glm::ivec2 half_size_{0};
    bool pyramid_ = false;
    double samples_ = 0;
};

pathlet::PassTypeInfo lineao_type() {
    return pathlet::PassTypeBuilder("lineao",
                                    "LineAO (Eichelbaum et al. 2013): multi-radius screen-space ambient occlusion "
                                    "for dense lines; 1 = unoccluded")
        .param_int("samples", 16, 1, 128,
                   "s_h: samples of level 0; level l takes s_h/(l+1) (16: 29 in all; the study used 32, 58 in all)")
        .param_int("radii", 3, 1, kMaxLevels, "s_r: number of radii (hemispheres / pyramid levels)")
        .param_float("r0", 2.0, 0.0, 100.0, "first sampling radius in pixels (about the line width on screen)")
        .param_float("line_width", 0.0, 0.0, 1e6,
                     "world units per radius step (0 = auto, as the gbuffer's): r_l grows by zoom(P)*line_width px "
                     "per level; set it to the "
                     "gbuffer's line width so one step is one line width on screen")
        .param_float("width_factor", 1.0, 0.01, 100.0,
                     "the auto width (line_width 0) times this, as the line pass's: tie both to one graph variable")
        .param_enum("radius_growth", "linear", {"linear", "running_sum"},
                    "linear: r_l = r0 + l*w (paper eq. 6); running_sum: r0 + (0, 2.5, 6, 10.5, ..)*w, the authors' "
                    "1.5/4/7.5 sum (w = line width on screen)")
        .param_float("strength", 1.0, 0.0, 5.0, "total strength: AO = 1 - strength/s_r * sum of levels")
        .param_float("density_weight", 1.0, 0.001, 2.0, "scales delta(l) = (1 - l/s_r)^2, the depth cut-off")
        .param_float("delta0", 1e-6, 0.0, 0.1, "delta0: smallest depth difference (normalised) that occludes")
        .param_bool("use_pyramid", true, "level l samples mip l of `pyramid` (when connected); else level 0")
        .param_bool("occluder_light", true, "add the occluder's diffuse reflection to the light term")
        .param_vec3("light_dir", glm::vec3(0, 0, 1), "direction to the light in view space (normalised)")
        .param_float("exponent", 100.0, 1.0, 1000.0, "Blinn-Phong exponent of the occluder's specular term")
        .param_int("seed", 1, 0, 2147483647, "seed of the fixed per-pixel noise (same image every run)")
        .param_enum("resolution", "full", {"full", "half"},
                    "half: the term for one pixel in each 2x2 block, then a depth-aware upsampling (about a "
                    "quarter of the cost; measured difference in the README); full: every pixel")
        .input_texture("normal_depth", "rgba16f", "view-space normal (xyz), normalised linear depth (w)")
        .input_texture("pyramid", "rgba16f", "gauss_pyramid output; mip l is read by level l", true)
        .input_texture("zoom", "r32f", "pixels per world unit at the fragment")
        .input_texture("color", "any", "line colour (not used by the AO term; accepted for graph symmetry)", true)
        .input_texture("depth", "depth24", "G-buffer depth; when connected, background pixels are skipped", true)
        .output_texture("ao", "r16f", "ambient occlusion, 1 = unoccluded, background 1")
        .make<LineAO>();
}

}  // namespace

PATHLET_PLUGIN("lineao", { sink->add(lineao_type()); })
