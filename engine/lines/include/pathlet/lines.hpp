// The line kit: what every pass that draws pathlets uses, in tree or out (gbuffer, isl,
// geometric_fade, a researcher's fade). It owns the shared line parameters (declared once),
// the time-window draw, colour maps, halos and the tube normal and depth; a pass plugs in
// small GLSL hooks instead of forking the shaders:
//
//   width hook (.geom):  float line_width_hook(LinePoint p)             multiplier of the width
//   colour hook (.frag): vec4  line_color_hook(vec4 rgba, LinePoint p)   colour and opacity
//
// LinePoint (engine/lines/shaders/line_hooks.glsl) carries the point's time, its age in the window (0 at
// the head, 1 at the tail), the arc length from the head and from the tail, speed, line id.
// The kit derives the quad, tube normal and tube depth from the hooked width, so a taper is
// a hook and a parameter list. A whole fade strategy (see plugins/example_fade/):
//
//   class Fade : public pathlet::lines::GBufferPass {
//   public:
//       Fade() : GBufferPass({.color = "fade_color.frag"}) {}
//       void set_uniforms(pathlet::PassContext& ctx, const pathlet::ShaderProgram& p) override {
//           p.set("u_strength", ctx.params().f("strength"));
//       }
//   };
//   PATHLET_PLUGIN("fade", { sink->add(pathlet::lines::gbuffer_pass_type("fade", "...")
//                                .param_float("strength", 1, 0, 1, "...").make<Fade>()); })
#pragma once

#include <pathlet/gpu_scene.hpp>
#include <pathlet/pass.hpp>
#include <pathlet/shader.hpp>

#include <string>
#include <vector>

namespace pathlet::lines {

// Shader storage binding the kit uses for its per-pathlet buffer; passes use other points.
constexpr GLuint kPathletBinding = 7;

// GLSL hook files, found on the shader path (the pass's own folder first). Empty: the kit's
// default (full width; the colour map as it is).
struct Hooks {
    std::string width = {};  // .geom defining float line_width_hook(LinePoint p)
    std::string color = {};  // .frag defining vec4 line_color_hook(vec4 rgba, LinePoint p)
};

// Colour map names, in the order of the COLORMAP_* constants in shaders/colormap.glsl.
const std::vector<std::string>& colormaps();
int colormap_index(const std::string& name);

// The shared line parameters: window, line_width, halo, halo_color, halo_depth, colormap,
// speed_min, speed_max, background, lod. Declared here once for every line pass.
PassTypeBuilder& declare_params(PassTypeBuilder& b);
// `window` and `line_width` alone (the first two), for passes that follow the pathlets or their
// tubes without drawing them (line_density, volume_ao).
PassTypeBuilder& declare_window_param(PassTypeBuilder& b);
PassTypeBuilder& declare_line_width_param(PassTypeBuilder& b);
// LineAO's G-buffer outputs: color, normal_depth, zoom, depth, optional line_id, edge, tangent.
PassTypeBuilder& declare_gbuffer_outputs(PassTypeBuilder& b);
// A G-buffer line pass type: the shared parameters and the G-buffer outputs; add your own
// parameters and finish with .make<YourPass>().
PassTypeBuilder gbuffer_pass_type(const std::string& type, const std::string& doc);

// A program of the kit's vertex and geometry stages (line_kit.vert, line_quad.geom), the
// width hook, the pass's fragment shader(s) and the colour hook. Cached by the context.
ShaderProgram& program(PassContext& ctx, const std::vector<std::string>& fragment, const Hooks& hooks = {},
                       const std::vector<std::string>& defines = {});

// Draws the pathlets of the current time window: sets the kit's uniforms on `prog` (in use),
// uploads the per-pathlet buffer, draws with depth testing, reports the segment count.
class Drawer {
public:
    Drawer() = default;
    Drawer(const Drawer&) = delete;
    Drawer& operator=(const Drawer&) = delete;
    ~Drawer();
    void draw(PassContext& ctx, const ShaderProgram& prog);
    // The same uniforms and buffer without drawing (for a pass that issues its own draws).
    void prepare(PassContext& ctx, const ShaderProgram& prog);
    const GpuScene::Ranges& ranges() const { return ranges_; }
    // Depth test of the draw (default GL_LEQUAL). GL_ALWAYS keeps every fragment, e.g. for OIT,
    // while a bound depth target still records where fragments landed.
    void set_depth_func(GLenum f) { depth_func_ = f; }

    // Segments drawn in the last frame (after the level of detail).
    size_t segments() const { return lod_on_ ? strips_.segments : ranges_.segments; }

private:
    GLenum depth_func_ = GL_LEQUAL;
    GpuScene::Ranges ranges_;
    LineLod::Strips strips_;
    bool lod_on_ = false;
    GLuint index_buffer_ = 0;
    size_t index_capacity_ = 0;
    std::vector<glm::vec4> pathlets_;
    GLuint buffer_ = 0;
    size_t capacity_ = 0;
};

// Object-space AO from the line-density volume (the line_density pass; GLSL: the installed
// line_density.glsl and line_volume_ao.glsl, whose line_volume_ao_fragment(LineFrag) gives a
// fragment its own AO). The volume is a shader storage buffer at kDensityBinding: a header
// (grid size, origin, voxel size, window) and fixed-point cells (kDensityScale per voxel length).
constexpr GLuint kDensityBinding = 10;  // LINE_DENSITY_BINDING
constexpr GLuint kDensityUnit = 6;      // LINE_DENSITY_UNIT: texture unit of the cells
constexpr double kDensityScale = 65536.0;
constexpr size_t kDensityHeaderBytes = 48;
// Parameters of the AO estimate, declared once: reach (line widths), ao_scale, directions, steps.
PassTypeBuilder& declare_volume_ao_params(PassTypeBuilder& b);
// What a pass that evaluates line_volume_ao.glsl keeps: the cells as a 3D texture.
class VolumeAo {
public:
    VolumeAo() = default;
    VolumeAo(const VolumeAo&) = delete;
    VolumeAo& operator=(const VolumeAo&) = delete;
    ~VolumeAo();
    // Defines that compile the direction and step counts into line_volume_ao.glsl.
    static std::vector<std::string> defines(const Params& p);
    // Every frame, with `prog` in use: sets the uniforms (the radius is half the pass's
    // line_width), binds the volume of input pin `pin` and copies its cells into the texture
    // at kDensityUnit (a wait for the pass that built it).
    void bind(PassContext& ctx, const ShaderProgram& prog, const std::string& pin = "density");

private:
    GLuint texture_ = 0;
    glm::ivec3 dims_{0};
};

// The end fade of a pathlet (engine/lines/shaders/line_fade.glsl: float line_end_fade(LinePoint)), shared
// by every fade strategy: parameters tail_fade, head_fade, fade_measure (time | arc_length),
// fade_curve (linear | smooth | round) and fade_floor, declared once here. In arc-length mode
// the lengths are fractions of a typical pathlet (median speed x window), so the same values
// read alike in both modes while every pathlet gets the same fade length on screen.
PassTypeBuilder& declare_fade_params(PassTypeBuilder& b, double tail_fade, double head_fade,
                                     const std::string& what_fades);
class EndFade {
public:
    // Call from setup(): measures the typical pathlet length of the scene for the window.
    void setup(PassContext& ctx);
    // Sets line_fade.glsl's uniforms on `prog`.
    void set_uniforms(PassContext& ctx, const ShaderProgram& prog) const;
    float typical_length() const { return reference_; }

private:
    float reference_ = 1.0f;
};

// Where the lines can be on screen this frame: the scene's bounding box, widened by the line
// width, projected with the frame's camera, plus pad_px pixels; {x0, y0, x1, y1} in pixels
// of the output (GL's bottom-left origin, end exclusive), clamped to it. The whole output when
// the box reaches behind the camera. A post pass scissors to it to skip the empty border.
glm::ivec4 screen_rect(const PassContext& ctx, int pad_px);
// The same for a scene, camera and output size (what the PassContext form passes in).
glm::ivec4 screen_rect(const GpuScene& scene, const Camera& camera, glm::ivec2 size, int pad_px);

// Scissors every draw to a rectangle ({x0, y0, x1, y1}, as screen_rect gives) while it lives:
// `ScopedScissor clip(lines::screen_rect(ctx, pad));` around a post pass's draws.
class ScopedScissor {
public:
    explicit ScopedScissor(glm::ivec4 rect);
    ~ScopedScissor();
    ScopedScissor(const ScopedScissor&) = delete;
    ScopedScissor& operator=(const ScopedScissor&) = delete;
};

// `rect` (pixels of level 0) on mip `level`: scaled down and rounded outwards, plus pad_px
// texels of that level, clamped to `size` (the level's size).
glm::ivec4 rect_at_level(glm::ivec4 rect, int level, int pad_px, glm::ivec2 size);

// Clears the bound framebuffer's colour attachment `index` / depth, whatever the masks were.
void clear_color(int index, glm::vec4 value);
void clear_color_int(int index, glm::ivec4 value);
void clear_depth(float value = 1.0f);

// The G-buffer line pass, ready to subclass: `gbuffer` is this with no hooks, a fade is this
// with a hook and its uniforms. Writes the outputs of declare_gbuffer_outputs().
class GBufferPass : public Pass {
public:
    explicit GBufferPass(Hooks hooks = {}) : hooks_(std::move(hooks)) {}
    void setup(PassContext& ctx) override;
    void execute(PassContext& ctx) override;

protected:
    // The hooks' own uniforms, every frame, with the program in use. A name the program does
    // not declare throws (a typo must not silently switch a fade off).
    virtual void set_uniforms(PassContext& ctx, const ShaderProgram& prog) {}

    Hooks hooks_;
    ShaderProgram* prog_ = nullptr;
    Drawer drawer_;
    bool write_id_ = false;
    bool write_edge_ = false;
    bool write_tangent_ = false;
};

// A G-buffer line pass whose hook uses the kit's end fade (line_fade.glsl): geometric_fade
// tapers the width with it, fade_core keeps the opaque core. Declare its parameters with
// declare_fade_params; override set_uniforms (calling this one) to add your own.
class EndFadePass : public GBufferPass {
public:
    using GBufferPass::GBufferPass;
    void setup(PassContext& ctx) override {
        GBufferPass::setup(ctx);
        fade_.setup(ctx);
    }

protected:
    void set_uniforms(PassContext& ctx, const ShaderProgram& prog) override { fade_.set_uniforms(ctx, prog); }
    EndFade fade_;
};

}  // namespace pathlet::lines
