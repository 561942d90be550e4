// The pass contract. A pass type declares its parameters and pins ONCE (PassTypeBuilder);
// that declaration drives graph validation, `--set` overrides, `pathlet passes --describe`,
// the viewer's panels and the docs, and it binds: a parameter `radius` reaches every program
// of the pass as its uniform `u_radius`, a texture pin `ao` as its sampler (or image) `u_ao`.
// The instance then implements setup() (shaders, GL objects) and execute().
#pragma once

#include <pathlet/gl.hpp>
#include <pathlet/hook.hpp>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pathlet {

using json = nlohmann::json;

// ---- declarations ---------------------------------------------------------------------

enum class ParamType { Bool, Int, Float, String, Enum, Vec3, Color };
const char* to_string(ParamType t);

struct ParamDecl {
    std::string name;
    ParamType type = ParamType::Float;
    json def;                                        // default value, of the declared type
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    std::vector<std::string> choices;                // Enum only
    std::string doc;
    bool pixels = false;  // a length in picture pixels: bound as u_<name> times the pixel scale
    // A string naming a hook file of this role (pathlet/hook.hpp): the uniforms the file
    // annotates with @param become parameters of the pass instance.
    std::optional<HookRole> hook;
    std::string origin;   // a parameter a hook declared: "file.frag:12"
    // The lower end of a range whose upper end is the parameter `at_most` (ParamOptions).
    std::string at_most;
    double automatic_at_or_below = -std::numeric_limits<double>::infinity();

    // Checks and converts a JSON value (ints accepted for floats, "#rrggbb" for colours).
    // Returns an error message, or "" and sets `out`.
    std::string coerce(const json& in, json& out) const;
    // Parses a command-line string ("0.5", "true", "[1,0,0]", "#ff0000", "linear").
    std::string coerce_text(const std::string& text, json& out) const;
};

// How a parameter is bound (the trailing argument of the builder's param_* calls).
struct ParamOptions {
    // A length in picture pixels (a radius, a band): u_<name> gets it times the render's pixel
    // scale, so `render --ssaa N` looks the same (ints are rounded).
    bool pixels = false;
    // The lower end of a range whose upper end is the parameter named here: the graph compiler
    // refuses a value above that one's, naming both (GLSL's clamp(x, lo, hi) is undefined for
    // lo > hi). Values at or below `automatic_at_or_below` stand for an automatic choice ("<= 0:
    // the data's") and are not compared.
    std::string at_most = {};
    double automatic_at_or_below = -std::numeric_limits<double>::infinity();
};

enum class PinKind { Texture, Buffer };
enum class PinDir { Input, Output };

// The shape of a pin (the trailing argument of the builder's pin calls):
//   .input_texture("pyramid", "rgba16f", "...", {.optional = true})
//   .output_texture("pyramid", "rgba16f", "...", {.mips = 0})
struct PinOptions {
    bool optional = false;  // may stay unconnected; the pass asks connected()
    int mips = 1;           // outputs and internal textures: mip levels; 0 = full chain
    float scale = 1.0f;     // outputs and internal textures: size = scale x output size
    bool persistent = false;  // internal textures and buffers: content kept across frames (not pooled)
    // Inputs: parameters this pass shares with what produced the input, which must have the same
    // value in both (the two draw the same fragments, or one reads what the other wrote in a
    // form both must know): each is compared with the nearest pass up the input's chain of
    // writers that declares it, and the graph compiler refuses a graph where they differ,
    // naming both passes. "*": every parameter of this pass.
    std::vector<std::string> same_params = {};
};
// The size of a buffer output: {.bytes = 1024}, {.bytes_per_pixel = 16}, or decided by the
// pass's resolved parameters, {.from_params = [](const json& p) { return ...; }} (a volume's grid).
struct BufferSize {
    size_t bytes = 0;            // fixed size, or ...
    size_t bytes_per_pixel = 0;  // ... proportional to the output's pixel count, or ...
    std::function<size_t(const json& params)> from_params = {};  // ... from the parameters
};

struct PinDecl {
    std::string name;
    PinDir dir = PinDir::Input;
    PinKind kind = PinKind::Texture;
    std::string format = "any";  // texture format name (see formats.hpp), or "any" for inputs
    int mips = 1;                // outputs: mip levels; 0 = full chain
    float scale = 1.0f;          // outputs: default size = scale x output size
    size_t bytes = 0;            // buffer outputs: fixed size, or ...
    size_t bytes_per_pixel = 0;  // ... size proportional to the output's pixel count
    bool optional = false;       // may stay unconnected; an unconnected optional output gets no
                                 // resource (connected() is false), a required one an implicit one
    bool internal = false;       // the pass's own texture or buffer (an output no graph may bind): the
                                 // engine allocates and pools it like any transient, the pass uses it by name
    bool persistent = false;     // internal: kept across frames, never pooled
    std::vector<std::string> same_params;  // inputs: PinOptions::same_params
    std::string doc;
    // Buffer outputs sized by the pass's resolved parameters (e.g. a volume's grid); takes
    // precedence over bytes/bytes_per_pixel. The compiler, `graph --plan` and pooling see it.
    std::function<size_t(const json& params)> bytes_from_params;
};
// "in", "out", or "internal" for a pass's own texture (never bound in a graph): how listings name it.
const char* direction_name(const PinDecl& p);

// The GLSL define that holds a buffer pin's binding point: "density" -> "DENSITY_BINDING".
std::string binding_define(const std::string& pin);

class Pass;
struct PassTypeInfo {
    std::string type;
    std::string doc;
    std::vector<ParamDecl> params;
    std::vector<PinDecl> pins;
    std::function<std::unique_ptr<Pass>()> create;
    std::string plugin_file;  // filled in by the plugin host
    bool side_effect = false; // never culled even without connected outputs (capture, stats)
    // The pass waits for the GPU in the frame loop on purpose (an exact reference reading a count
    // before it goes on): why, and the bool parameter that makes it wait ("": always). Any other
    // pass's wait after its first frame is a fault (PATHLET_GL_DEBUG and the latency mode count them).
    std::string gpu_wait_reason, gpu_wait_when;

    const ParamDecl* param(const std::string& name) const;
    const PinDecl* pin(const std::string& name) const;
    json default_params() const;
    std::string describe() const;  // the text of `pathlet passes --describe TYPE`
    std::string markdown() const;  // parameter and pin tables for the pass README (`--markdown`)
};

// One row per pass type (linked to its folder, what it does, its inputs and outputs): the
// index in passes/README.md (`pathlet passes --markdown`).
std::string index_markdown(const std::vector<const PassTypeInfo*>& types);

// Fluent builder: the single place a pass type states what it is.
class PassTypeBuilder {
public:
    PassTypeBuilder(std::string type, std::string doc);

    // Parameters: u_<name> in every program of the pass (bool and int as int, enum as the index
    // of its choice, vec3 and color as vec3; strings are not bound).
    PassTypeBuilder& param_bool(const std::string& name, bool def, const std::string& doc);
    PassTypeBuilder& param_int(const std::string& name, int def, int min, int max, const std::string& doc,
                               ParamOptions o = {});
    PassTypeBuilder& param_float(const std::string& name, double def, double min, double max, const std::string& doc,
                                 ParamOptions o = {});
    PassTypeBuilder& param_enum(const std::string& name, const std::string& def, std::vector<std::string> choices,
                                const std::string& doc);
    PassTypeBuilder& param_string(const std::string& name, const std::string& def, const std::string& doc);
    // The parameter naming the pass's hook file of `role` (its name from pathlet/hook.hpp:
    // color_hook, width_hook): the file's @param uniforms become the instance's parameters.
    PassTypeBuilder& param_hook(HookRole role, const std::string& def, const std::string& doc);
    PassTypeBuilder& param_vec3(const std::string& name, glm::vec3 def, const std::string& doc);
    PassTypeBuilder& param_color(const std::string& name, glm::vec3 def, const std::string& doc);
    // Any parameter, e.g. one reflected from a shader.
    PassTypeBuilder& param(ParamDecl d);

    // Pins: a texture pin `x` is bound to the sampler or image `u_x` of every program of the pass
    // before each execute().
    PassTypeBuilder& input_texture(const std::string& name, const std::string& format, const std::string& doc,
                                   PinOptions o = {});
    PassTypeBuilder& output_texture(const std::string& name, const std::string& format, const std::string& doc,
                                    PinOptions o = {});
    // A texture only this pass uses (a separable filter's intermediate, a half-resolution term):
    // never bound in a graph, allocated and pooled by the engine, `ctx.texture(name)` as any pin.
    PassTypeBuilder& internal_texture(const std::string& name, const std::string& format, const std::string& doc,
                                      PinOptions o = {});
    PassTypeBuilder& input_buffer(const std::string& name, const std::string& doc, PinOptions o = {});
    // A buffer only this pass uses (a statistics block, an index list it fills): never bound in a
    // graph, allocated by the engine (ctx.buffer(name), ctx.grow_buffer(name, bytes)), on binding
    // point ctx.buffer_binding(name) like any buffer pin. {.persistent = true} keeps its content
    // from frame to frame (it is then never pooled).
    PassTypeBuilder& internal_buffer(const std::string& name, const std::string& doc, BufferSize size,
                                     PinOptions o = {});
    // Buffer outputs: the size (BufferSize), and {.optional = true} for one written only when bound.
    PassTypeBuilder& output_buffer(const std::string& name, const std::string& doc, BufferSize size,
                                   PinOptions o = {});

    // The pass has a fragment and a compute version of its fullscreen work: declares the
    // parameter `impl` (auto | fragment | compute; auto follows auto_impl() below). The pass
    // compiles with ctx.fullscreen_program() and branches on ctx.use_compute().
    PassTypeBuilder& compute_version();

    // The pass does work outside the graph (writes files): the compiler never culls it.
    PassTypeBuilder& side_effect() {
        info_.side_effect = true;
        return *this;
    }

    // The pass waits for the GPU in the frame loop, on purpose (PassTypeInfo::gpu_wait_reason).
    PassTypeBuilder& waits_for_gpu(const std::string& reason, const std::string& when_bool_param = "") {
        info_.gpu_wait_reason = reason;
        info_.gpu_wait_when = when_bool_param;
        return *this;
    }

    template <class P>
    PassTypeInfo make() {
        info_.create = [] { return std::unique_ptr<Pass>(new P()); };
        return info_;
    }

private:
    PassTypeInfo info_;
};

// ---- run time -------------------------------------------------------------------------

// ---- fullscreen passes: fragment or compute ---------------------------------------------

// Which version of a fullscreen pass runs (the parameter `impl` of a pass with compute_version()).
enum class FullscreenImpl { fragment, compute };
// The software rasterizer a GL_RENDERER string names ("llvmpipe", "softpipe", "swrast",
// "SwiftShader", ...), or "" for a hardware GPU.
std::string software_rasterizer(const std::string& gl_renderer);
// What `impl=auto` runs: compute on a hardware GPU (a datacenter GPU runs fragment work on a
// small part of the chip: a 29-tap pass took 1.5 ms as fragment, 0.09 ms as compute on an
// H200), fragment on a software rasterizer (llvmpipe's compute was 3.5-4.6x slower).
FullscreenImpl auto_impl(const std::string& gl_renderer);
// The stat a pass with both versions reports every frame: 1 when compute ran, 0 for fragment
// (`bench` and the profiler's table print it).
inline constexpr const char* kComputeStat = "compute";

// Resolved parameter values of one pass instance (defaults + graph + variables + --set).
class Params {
public:
    Params() = default;
    Params(std::string pass, json values, const PassTypeInfo* type = nullptr)
        : pass_(std::move(pass)), v_(std::move(values)), type_(type) {}
    bool b(const std::string& n) const;
    int i(const std::string& n) const;
    float f(const std::string& n) const;
    std::string s(const std::string& n) const;
    glm::vec3 v3(const std::string& n) const;
    // An enum parameter as the index of its choice, or as your enum whose values follow the
    // declared choices: `enum class Mode { gaussian, box }; p.e<Mode>("mode")`.
    int index(const std::string& n) const;
    template <class E>
    E e(const std::string& n) const {
        return static_cast<E>(index(n));
    }
    const json& raw() const { return v_; }
    const PassTypeInfo* type() const { return type_; }

private:
    const json& at(const std::string& n) const;
    std::string pass_;
    json v_;
    const PassTypeInfo* type_ = nullptr;  // set by the engine: choices for index()
};

struct Texture {
    GLuint id = 0;
    int width = 0, height = 0, mips = 1;
    GLenum internal_format = 0;
    explicit operator bool() const { return id != 0; }
};

struct Buffer {
    GLuint id = 0;
    size_t bytes = 0;
    explicit operator bool() const { return id != 0; }
};

struct Camera {
    glm::mat4 view{1.0f}, proj{1.0f};
    glm::vec3 eye{0, 0, 1}, target{0}, up{0, 1, 0};
    float fov_y_deg = 45.0f, near_plane = 0.1f, far_plane = 100.0f;
};

class GpuScene;
class ShaderProgram;
class ShaderSource;
struct ShaderStage;
struct PassContextImpl;

// Pathlet's shared data folder (shaders/, graphs/, fonts/): share/pathlet beside libpathlet's
// folder (build tree, install, bundle alike), or $PATHLET_SHARE_DIR. For data files a pass ships.
std::string share_dir();

// What a pass sees, in setup() and in execute(). Implemented by the executor.
class PassContext {
public:
    explicit PassContext(PassContextImpl* impl) : impl_(impl) {}

    const std::string& pass_name() const;
    const Params& params() const;
    glm::ivec2 output_size() const;
    // Render pixels per picture pixel (1; N under `render --ssaa N`). Multiply parameters given
    // in pixels (radii, widths, tolerances) by it so a supersampled frame looks the same.
    float pixel_scale() const;

    bool connected(const std::string& pin) const;   // optional inputs may be unconnected
    Texture texture(const std::string& pin) const;  // throws naming the pass and pin when unbound
    Buffer buffer(const std::string& pin) const;
    // Makes the buffer bound to an output pin at least `bytes` large (a new store, content not
    // kept), for passes whose need is known only at run time (e.g. OIT node storage). Throws
    // GL out-of-memory as a PassError like any GL error.
    Buffer grow_buffer(const std::string& pin, size_t bytes);

    const GpuScene& scene() const;
    // Where the pass's shaders come from: the search path (PATHLET_SHADER_PATH, the pass's own
    // folder, the shared shaders, the graph's folders) and the hook files the graph resolved.
    const ShaderSource& shaders() const;
    // Compiles (once, cached) a program from shader file names found on shaders()' path (the
    // pass's own folder first). Compile errors throw and name the file and line.
    // The program is bound by declaration: its uniforms u_<param> hold the pass's parameters
    // (again after every parameter change, before setup() runs), its samplers and images
    // u_<pin> the pins' textures (bound before each execute()). A uniform of that name whose
    // type does not fit the parameter is an error. Set what you derive yourself after that.
    ShaderProgram& program(const std::vector<std::string>& files, const std::vector<std::string>& defines = {});
    // The same from shader objects given explicitly (files found with shaders(): a hook after
    // the line kit's definitions, a fragment-style file compiled as compute).
    ShaderProgram& program_from(const std::vector<ShaderStage>& stages, const std::vector<std::string>& defines = {});
    // The storage-buffer binding point the engine gave buffer pin `pin` (declaration order among
    // the pass's buffer pins, from 0). Every program() of the pass has it as the define
    // binding_define(pin) ("nodes" -> NODES_BINDING), and the executor binds the pin's buffer
    // there before each execute(): `layout(std430, binding = NODES_BINDING) buffer ...`.
    int buffer_binding(const std::string& pin) const;
    // Sets u_<param> on a program made elsewhere (program() does this for its own).
    void bind_params(const ShaderProgram& prog) const;

    // The buffer bound to `pin` as a buffer texture of texel format `format` (GL_RGBA32UI for
    // uvec4 nodes), for texelFetch or imageLoad/imageStore; the engine owns the view and makes a
    // new one when the buffer grows. Bind it with prog.bind_texture / bind_image.
    GLuint buffer_texture(const std::string& pin, GLenum format);

    // Binds a framebuffer whose colour attachments are the given output pins (in order, as
    // locations 0..n-1) and optional depth pin, and sets the viewport to their size. With no
    // pins at all: a framebuffer with no attachments, of the output size (a raster whose
    // fragments only write images or buffers).
    void bind_framebuffer(const std::vector<std::string>& color_pins, const std::string& depth_pin = "",
                          int mip = 0);

    // Writes the texture bound to `pin` to an image file (the extension picks the format: PNG,
    // EXR keeps floats), under a temporary name and then renamed; `pattern` may hold {pass} and
    // {frame:05}. Returns the file written.
    std::string write_image(const std::string& pin, const std::string& pattern);

    // Per-frame facts (valid in execute()).
    uint64_t frame_index() const;
    double time() const;        // animation time in seconds
    const Camera& camera() const;
    // Statistics reported with the timing table (e.g. "segments drawn").
    void stat(const std::string& name, double value);
    // Frame `frame` (its frame_index(), possibly an earlier frame's: a count read back late) lost
    // part of its picture, e.g. fragments dropped on overflow. A run ends with the line
    // "incomplete frames: N of M (...)" (render, bench, Python).
    void frame_incomplete(uint64_t frame);
    // Fullscreen passes with a compute version (PassTypeBuilder::compute_version()):
    // The parameter `impl` resolved on this context's renderer (auto_impl for `auto`).
    bool use_compute() const;
    // The pass's fullscreen shader `file` (written once for both, see shaders/fullscreen_pass.glsl):
    // with use_compute() compiled as a compute shader with FULLSCREEN_COMPUTE defined, else as
    // the fragment stage behind fullscreen.vert. Bound by declaration like program(): outputs
    // the compute version writes are images u_<pin> (level 0; other levels: bind_image).
    ShaderProgram& fullscreen_program(const std::string& file, std::vector<std::string> defines = {});
    // Runs a compute program over every pixel of `rect` ({x0, y0, x1, y1}, end exclusive, as
    // lines::screen_rect gives; nothing when empty): work groups of the program's local size,
    // fullscreen_pixel() in the shader skips the overhang. With `depth_pin` (a G-buffer depth)
    // only pixels on geometry (depth < 1), as draw_fullscreen_on_geometry does. Ends with the
    // memory barrier every later reader needs (texture fetch, framebuffer, copies, read-back).
    void dispatch_fullscreen(ShaderProgram& prog, glm::ivec4 rect, const std::string& depth_pin = "");
    // The same over the whole output.
    void dispatch_fullscreen(ShaderProgram& prog, const std::string& depth_pin = "");

    // A full-screen triangle: bind a program first; vertex shader from shaders/fullscreen.vert.
    void draw_fullscreen();
    // The same, but only where the bound framebuffer's depth attachment (a G-buffer depth)
    // is < 1, i.e. on geometry: the early depth test skips background pixels, which on
    // llvmpipe skips whole empty tiles. `prog` must use fullscreen.vert. Leaves depth state off.
    void draw_fullscreen_on_geometry(ShaderProgram& prog);

protected:
    PassContextImpl* impl_;
};

// GL state at the start of setup() and execute(), whatever the previous pass left: no program,
// vertex array or framebuffer bound (draw framebuffer 0), viewport = output size; depth test,
// blending, face culling, scissor and stencil test off; depth function LESS, depth writes on,
// colour writes on, blend function (ONE, ZERO); the pass's texture pins bound to the units of
// their u_<pin> samplers (and images), nothing else bound. A pass changes what it needs and
// need not restore it.
class Pass {
public:
    virtual ~Pass() = default;
    // Once, with the GL context current, after resources exist (and again after a resize
    // or parameter change). Compile programs and create pass-private GL objects here.
    virtual void setup(PassContext& ctx) {}
    // Every frame.
    virtual void execute(PassContext& ctx) = 0;
    // Once at the end of a run (render, bench, Python), GL current: wait for what is still in
    // flight that can tell of an incomplete frame (late counts) and report it.
    virtual void finish(PassContext& ctx) {}
};

}  // namespace pathlet
