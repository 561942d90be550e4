// lineao: the LineAO term per pixel (shared/LINEAO.md). The per-level constants (sample
// counts, radius growth, delta(l), the kernel's starting angle) are computed here when the
// parameters change and passed as uniforms, so the shader has uniform loop bounds and no
// recompiles; the kernel itself is generated in lineao.frag. The parameters the shader uses
// as they are (u_r0, u_strength, u_radii, ...) and the input textures reach it by declaration.
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

enum class Growth { linear, running_sum };
enum class Resolution { full, half };

Levels make_levels(const pathlet::Params& p) {
    Levels L;
    L.count = std::clamp(p.i("radii"), 1, kMaxLevels);
    const int s_h = std::max(1, p.i("samples"));
    const bool running_sum = p.e<Growth>("radius_growth") == Growth::running_sum;
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
        compute_ = ctx.use_compute();
        // Half resolution: the term for one pixel in four into the internal texture `half`, then
        // a depth-aware upsampling into `ao` (lineao_upsample.frag).
        half_ = p.e<Resolution>("resolution") == Resolution::half;
        std::vector<std::string> defines = pathlet::whole_exponent("LINEAO_EXPONENT", p.f("exponent"));
        if (half_) defines.push_back("LINEAO_HALF");  // the compute version's target: the image u_half
        prog_ = &ctx.fullscreen_program("lineao.frag", defines);
        const Levels L = make_levels(p);
        glm::vec3 light = p.v3("light_dir");
        light = glm::length(light) > 1e-6f ? glm::normalize(light) : glm::vec3(0, 0, 1);
        const GLuint id = prog_->id();
        glProgramUniform1iv(id, prog_->loc("u_count"), L.count, L.samples);
        glProgramUniform1fv(id, prog_->loc("u_growth"), L.count, L.growth);
        glProgramUniform1fv(id, prog_->loc("u_delta"), L.count, L.delta);
        glProgramUniform2fv(id, prog_->loc("u_level_dir"), L.count, glm::value_ptr(L.start[0]));
        prog_->set("u_lod_offset", int(std::lround(std::log2(std::max(ctx.pixel_scale(), 1.0f)))));
        prog_->set("u_step_width", pathlet::lines::line_width(ctx));
        const bool pyramid = p.b("use_pyramid") && ctx.connected("pyramid");
        prog_->set("u_from_pyramid", pyramid ? 1 : 0);
        prog_->set("u_max_lod", pyramid ? ctx.texture("pyramid").mips - 1 : 0);
        prog_->set("u_light", light);
        prog_->set("u_spec_cut", std::pow(1e-4f, 1.0f / p.f("exponent")));
        samples_ = double(L.total);
        if (half_) {
            upsample_ = &ctx.fullscreen_program("lineao_upsample.frag");
            upsample_->set("u_inv_sigma_d", 1.0f / 0.01f);
        }
    }

    void execute(pathlet::PassContext& ctx) override {
        // Covered pixels lie inside the lines' screen rectangle; outside it the term stays 1.
        const glm::ivec4 rect = pathlet::lines::screen_rect(ctx, 2);
        const float one = 1.0f;
        glClearTexImage(ctx.texture("ao").id, 0, GL_RED, GL_FLOAT, &one);
        if (half_) {
            const pathlet::Texture half = ctx.texture("half");
            glClearTexImage(half.id, 0, GL_RED, GL_FLOAT, &one);
            const glm::ivec4 half_rect = pathlet::lines::rect_at_level(rect, 1, 1, glm::ivec2(half.width, half.height));
            if (compute_) {
                ctx.dispatch_fullscreen(*prog_, half_rect);
            } else {
                ctx.bind_framebuffer({"half"});
                prog_->use();
                pathlet::lines::ScopedScissor clip(half_rect);
                ctx.draw_fullscreen();  // background texels return 1 at once
            }
            draw_covered(ctx, *upsample_, rect);
        } else {
            draw_covered(ctx, *prog_, rect);
        }
        ctx.stat("samples per pixel", samples_);
        ctx.stat(pathlet::kComputeStat, compute_ ? 1.0 : 0.0);
    }

private:
    // Into `ao` inside `rect`: with the G-buffer depth only where there is geometry (the
    // background stays 1, as cleared), else every pixel.
    void draw_covered(pathlet::PassContext& ctx, pathlet::ShaderProgram& prog, glm::ivec4 rect) const {
        if (compute_) {
            ctx.dispatch_fullscreen(prog, rect, ctx.connected("depth") ? "depth" : "");
            return;
        }
        pathlet::lines::ScopedScissor clip(rect);
        if (ctx.connected("depth")) {
            ctx.bind_framebuffer({"ao"}, "depth");
            ctx.draw_fullscreen_on_geometry(prog);
        } else {
            ctx.bind_framebuffer({"ao"});
            prog.use();
            ctx.draw_fullscreen();
        }
    }

    pathlet::ShaderProgram* prog_ = nullptr;
    pathlet::ShaderProgram* upsample_ = nullptr;
    bool half_ = false, compute_ = false;
    double samples_ = 0;
};

pathlet::PassTypeInfo lineao_type() {
    return pathlet::PassTypeBuilder("lineao",
                                    "LineAO (Eichelbaum et al. 2013): multi-radius screen-space ambient occlusion "
                                    "for dense lines; 1 = unoccluded")
        .param_int("samples", 16, 1, 128,
                   "s_h: samples of level 0; level l takes s_h/(l+1) (16: 29 in all; the study used 32, 58 in all)")
        .param_int("radii", 3, 1, kMaxLevels, "s_r: number of radii (hemispheres / pyramid levels)")
        .param_float("r0", 2.0, 0.0, 100.0, "first sampling radius in pixels (about the line width on screen)",
                     {.pixels = true})
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
                    "quarter of the cost; measured difference in docs/quality.md); full: every pixel")
        .input_texture("normal_depth", "rgba16f", "view-space normal (xyz), normalised linear depth (w); its line pass's "
                       "line_width and width_factor must be this pass's",
                       {.same_params = {"line_width", "width_factor"}})
        .input_texture("pyramid", "rgba16f", "gauss_pyramid output; mip l is read by level l", {.optional = true})
        .input_texture("zoom", "r32f", "pixels per world unit at the fragment")
        .input_texture("color", "any", "line colour (not used by the AO term; accepted for graph symmetry)",
                       {.optional = true})
        .input_texture("depth", "depth24", "G-buffer depth; when connected, background pixels are skipped",
                       {.optional = true})
        .output_texture("ao", "r16f", "ambient occlusion, 1 = unoccluded, background 1")
        .internal_texture("half", "r16f", "resolution=half: the term for the first pixel of each 2x2 block",
                          {.scale = 0.5f})
        .compute_version()
        .make<LineAO>();
}

}  // namespace

PATHLET_PLUGIN("lineao", { sink->add(lineao_type()); })
