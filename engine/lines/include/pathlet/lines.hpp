// The line kit: what every pass that draws pathlets uses, in tree or out (gbuffer, isl,
// fill_list, geometric_fade, fade_core, a researcher's own). It owns the shared line
// parameters (declared once), the time-window draw, colour maps, halos and the tube normal
// and depth; a pass plugs in small GLSL hook files instead of forking the shaders:
//
//   width hook (.geom):  float line_width_hook(LinePoint p)             multiplier of the width
//   colour hook (.frag): vec4  line_color_hook(vec4 rgba, LinePoint p)   colour and opacity
//
// Every kit pass has the parameters `color_hook` and `width_hook`, so a fade strategy is one
// GLSL file that every line pipeline accepts (opaque G-buffer, OIT lists, ISL):
//
//   pathlet render variant2_oit --set fill.color_hook=my_fade.frag
//
// and the uniforms the hook annotates with @param become that pass's parameters, declared once,
// in the shader (validated, --set, describe, viewer panels; bound to u_<name>):
//
//   uniform float u_start;  // @param 0.3 [0, 1] "age where the fade begins"
//
// A hook file is only its function (and its @param uniforms): the kit compiles it after its
// definitions (line_hooks.glsl) under the engine's #version; a file's own #version and
// #include "line_hooks.glsl" still work. Compile errors name the hook's file and line.
//
// LinePoint (shaders/line_hooks.glsl) carries the point's time, its age in the window (0 at
// the head, 1 at the tail), the arc length from the head and from the tail, speed, line id,
// its arc length along the whole line and its position in data coordinates. A hook that needs
// data of its own (per line, per segment) reads the pass's optional input buffer `hook_buffer`
// through line_hook_buffer.glsl (a uint array; e.g. shaders/oo_opacity.glsl).
// The kit derives the quad, tube normal and tube depth from the hooked width. Its own fades are
// hook files: fade_opacity.frag (variant 2's end fade), fade_width.geom (variant 3's taper),
// on line_fade.glsl's parameters; fade_core keeps where a colour hook's opacity reaches core_alpha. A pass with resources of its own is a
// small C++ class on GBufferPass or Drawer (see plugins/example_fade/).
#pragma once

#include <pathlet/buffer_texture.hpp>
#include <pathlet/gpu_scene.hpp>
#include <pathlet/pass.hpp>
#include <pathlet/shader.hpp>

#include <memory>
#include <string>
#include <vector>

namespace pathlet::lines {

// GLSL hook files: as a pass type names its defaults (file names on the shader path), or as the
// graph resolved them for a pass (found files, ctx.shaders()). Empty: the kit's default (full
// width; the colour map as it is, opaque).
struct Hooks {
    std::string width = {};  // .geom (or .glsl) defining float line_width_hook(LinePoint p)
    std::string color = {};  // .frag (or .glsl) defining vec4 line_color_hook(vec4 rgba, LinePoint p)
};
// The hook files the graph resolved for this pass (its color_hook and width_hook, found).
Hooks hooks(const PassContext& ctx);
// One hook file as the shader object its role needs (pathlet/hook.hpp: the colour hook a
// fragment object, the width hook a geometry object), after the kit's definitions
// (line_hooks.glsl on `source`'s path). program() builds its stages with it; `pathlet validate`
// compiles each hook alone with it.
ShaderStage hook_stage(const ShaderSource& source, HookRole role, const std::string& file);

// Colour map names, in the order of the COLORMAP_* constants in shaders/colormap.glsl (an enum
// parameter's params.index("colormap") is the constant).
const std::vector<std::string>& colormaps();

// The shared line parameters: window, line_width, width_factor, halo, halo_min_px, halo_color,
// halo_depth, colormap, speed_min, speed_max, background, lod, cull, and the hook files
// color_hook and width_hook (their defaults for this pass type in `defaults`), and the optional
// input buffer hook_buffer for the hooks. Declared here once for every line pass.
PassTypeBuilder& declare_params(PassTypeBuilder& b, const Hooks& defaults = {});
// `window` alone, and `line_width` with `width_factor` (the first three of the above), for
// passes that follow the pathlets or their tubes without drawing them (line_density, volume_ao).
PassTypeBuilder& declare_window_param(PassTypeBuilder& b);
PassTypeBuilder& declare_line_width_params(PassTypeBuilder& b);
// The part of the lines a pass shows at time t: [t - window, t], or every line whole
// (t0 = t1 = 0, windowed false) when window <= 0 or the data has no time (streamlines).
struct TimeWindow {
    double t0 = 0, t1 = 0;
    bool windowed = false;
};
TimeWindow time_window(const GpuScene& scene, float window, double t);
// The world-space width the kit draws with: line_width, or with 0 the data's auto width times
// width_factor (the parameters above).
float line_width(const PassContext& ctx);
// LineAO's G-buffer outputs: color, normal_depth, zoom, depth, optional line_id, edge, tangent.
// `optional`: every one may stay unbound (a pass that writes a G-buffer only when a graph asks,
// as fill_list does).
PassTypeBuilder& declare_gbuffer_outputs(PassTypeBuilder& b, bool optional = false);
// The G-buffer's colour targets a pass's graph binds, in location order, and the defines that
// give line_gbuffer_out.glsl's outputs (written by line_gbuffer_write) their locations.
struct GBufferTargets {
    std::vector<std::string> pins;
    std::vector<std::string> defines;
    std::vector<int> rows;  // per pin, its row of the kit's target table (background value, type)
};
GBufferTargets gbuffer_targets(const PassContext& ctx);
// Binds the targets with the pass's `depth`, clears them to their background values and the
// depth to 1, and puts `prog` in use with its u_zoom_scale set: a G-buffer pass's frame start.
void bind_gbuffer(PassContext& ctx, const GBufferTargets& targets, const ShaderProgram& prog);
// A G-buffer line pass type: the shared parameters and the G-buffer outputs; add your own
// parameters and finish with .make<YourPass>() (.make<GBufferPass>() for a type that only
// names its default hooks).
PassTypeBuilder gbuffer_pass_type(const std::string& type, const std::string& doc, const Hooks& defaults = {});

// A program of the kit's vertex and geometry stages (line_kit.vert, line_quad.geom), the
// width hook, the pass's fragment shader(s) and the colour hook. Cached by the context.
ShaderProgram& program(PassContext& ctx, const std::vector<std::string>& fragment, const Hooks& hooks = {},
                       const std::vector<std::string>& defines = {});

class ChunkCuller;
// GPU memory a culling line pass keeps for a scene of `chunks` chunks and `segments` segments:
// per chunk its state and strip, and GL_LINES indices for every segment (what `pathlet graph
// --plan` reports).
size_t culling_bytes(size_t chunks, size_t segments);

// Draws the pathlets of the current time window: sets the kit's uniforms on `prog` (in use),
// uploads the per-pathlet buffer, draws with depth testing, reports the segment count. With the
// pass's `cull` parameter (kit parameter, on by default) and at least `cull_min_segments` data
// segments in the window, the chunks are culled on the GPU: frustum culling, and with a
// depth-tested framebuffer two-phase occlusion culling against the pass's own depth, drawn
// from GPU-written commands (engine/lines/src/chunk_culler.hpp); the picture is the same.
class Drawer {
public:
    Drawer();
    Drawer(const Drawer&) = delete;
    Drawer& operator=(const Drawer&) = delete;
    ~Drawer();
    void draw(PassContext& ctx, const ShaderProgram& prog);
    // The same uniforms and buffer without drawing, for a pass that issues its own draws of
    // ranges() (no culling), with the level of detail's strips in strips().
    void prepare(PassContext& ctx, const ShaderProgram& prog);
    const GpuScene::Ranges& ranges() const { return ranges_; }
    const LineLod::Strips& strips() const { return strips_; }
    // Depth test of the draw (default GL_LEQUAL). GL_ALWAYS keeps every fragment, e.g. for OIT,
    // while a bound depth target still records where fragments landed (and nothing is
    // occlusion-culled).
    void set_depth_func(GLenum f) { depth_func_ = f; }
    // Off: frustum culling only, with any depth test. For a pass whose depth-tested targets are
    // not all it writes (fill_list's lists beside its G-buffer: a hidden fragment is still a node).
    void set_occlusion_culling(bool on) { occlusion_ = on; }
    // On: the blending the pass enabled stays on during the draw (blend-only OIT: WBOIT, MBOIT
    // accumulate with additive or multiplicative blending); off (default): the draw disables it.
    void set_blending(bool on) { blending_ = on; }

    // Segments the last unculled frame drew (after the level of detail); a culled frame's count
    // is on the GPU and reaches the pass's `segments` stat when the GPU is done.
    size_t segments() const { return segments_; }

private:
    void begin(PassContext& ctx, const ShaderProgram& prog);
    void select(const GpuScene& scene, const GpuScene::Ranges& r);
    void draw_ranges(PassContext& ctx, const GpuScene::Ranges& r);

    GLenum depth_func_ = GL_LEQUAL;
    bool occlusion_ = true;
    bool blending_ = false;
    GpuScene::Ranges ranges_;
    bool lod_on_ = false, width_hooked_ = false;
    struct {
        float px = 0, scale = 1;
        bool perspective = true;
        glm::vec3 eye{0};
    } lod_;
    LineLod::Strips strips_;  // the unculled draw's (culling selects on the GPU)
    GLuint index_buffer_ = 0;
    size_t index_capacity_ = 0;
    size_t segments_ = 0;
    float width_ = 0;
    std::vector<glm::vec4> pathlets_;
    GLuint buffer_ = 0;
    size_t capacity_ = 0;
    BufferTexture pathlets_view_;  // u_line_pathlets
    GLuint block_ = 0;  // the LineKit uniform block's buffer
    float typical_window_ = -1.0f, typical_length_ = 1.0f;  // cached per window length
    std::unique_ptr<ChunkCuller> culler_;
};

// The unit of the kit's arc-length measures (u_typical_length in every kit program): a typical
// pathlet's length, the median speed x window, or with whole lines (window <= 0) the median
// line length. A fade over a share of it is the same length on screen for every pathlet.
float typical_pathlet_length(const Scene& scene, float window);

// Object-space AO from the line-density volume (the line_density pass; GLSL: the installed
// line_density.glsl and line_volume_ao.glsl, whose line_volume_ao_fragment(LineFrag) gives a
// fragment its own AO). The volume is a shader storage buffer, a pass's buffer pin named
// kDensityPin (so on the engine's binding point for it): a header (grid size, origin, voxel size,
// window) and fixed-point cells (kDensityScale per voxel length). Both reach GLSL through
// density_defines(), so they are said here only.
constexpr const char* kDensityPin = "density";
constexpr double kDensityScale = 65536.0;
constexpr size_t kDensityHeaderBytes = 48;
// LINE_DENSITY_BINDING (the pass's `density` pin's binding point; 0 for a pass without one, which
// may then only use line_volume_ao.glsl's packing helpers) and LINE_DENSITY_SCALE for
// line_density.glsl.
std::vector<std::string> density_defines(const PassContext& ctx);
// Parameters of the AO estimate, declared once: reach (line widths), ao_scale, directions, steps.
PassTypeBuilder& declare_volume_ao_params(PassTypeBuilder& b);
// Per-fragment AO of an opaque core (graphs/variant2_*_ao.json) in a blend-only OIT pass: the
// optional inputs `ao` (bilateral's ao_smooth) and `core` (fade_core's normal_depth) and the
// parameter ao_tolerance, for a fragment stage that includes shaders/oit_blend.glsl.
PassTypeBuilder& declare_core_ao_inputs(PassTypeBuilder& b);
// {"CORE_AO"} when both inputs are connected, {} when neither; throws when only one is.
std::vector<std::string> core_ao_defines(const PassContext& ctx);
// What a pass that evaluates line_volume_ao.glsl keeps: the cells as a 3D texture.
class VolumeAo {
public:
    VolumeAo() = default;
    VolumeAo(const VolumeAo&) = delete;
    VolumeAo& operator=(const VolumeAo&) = delete;
    ~VolumeAo();
    // density_defines() and the direction and step counts compiled into line_volume_ao.glsl.
    static std::vector<std::string> defines(const PassContext& ctx);
    // Every frame, with `prog` in use: sets the uniforms (the radius is half the kit's line
    // width) and copies the cells of the pass's `density` pin (bound by declaration) into the
    // texture that u_density_cells samples.
    void bind(PassContext& ctx, const ShaderProgram& prog);

private:
    GLuint texture_ = 0;
    glm::ivec3 dims_{0};
    GLuint header_of_ = 0;  // the buffer whose header was read, its size, and the header's grid size
    size_t header_bytes_ = 0;
    glm::ivec4 header_{0};
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

// The G-buffer line pass: the pathlets through the pass's hooks into LineAO's inputs (the
// outputs of declare_gbuffer_outputs()). `gbuffer`, `geometric_fade` and `fade_core` are this
// with other default hooks; subclass it for a strategy that needs its own resources.
class GBufferPass : public Pass {
public:
    void setup(PassContext& ctx) override;
    void execute(PassContext& ctx) override;

protected:
    // Values you derive for your hook every frame, with the program in use (declared
    // parameters reach their uniforms by themselves). A name the program does not declare
    // throws (a typo must not silently switch a fade off).
    virtual void set_uniforms(PassContext& ctx, const ShaderProgram& prog) {}
    // Defines of line_gbuffer.frag beside the targets' (LINE_CORE: fade_core's threshold).
    virtual std::vector<std::string> fragment_defines(const PassContext& ctx) const { return {}; }

    ShaderProgram* prog_ = nullptr;
    Drawer drawer_;
    GBufferTargets targets_;  // the bound colour attachments, in location order
};

}  // namespace pathlet::lines
