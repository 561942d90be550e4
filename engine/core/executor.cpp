#include "executor.hpp"

#include "formats.hpp"
#include "frames/async_output.hpp"
#include "gl_context.hpp"
#include "graph/hook_params.hpp"
#include "image_io.hpp"
#include "plugin_host.hpp"
#include "profiler/profiler.hpp"

#include <pathlet/buffer_texture.hpp>
#include <pathlet/gpu_fence.hpp>
#include <pathlet/gl_limits.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace pathlet {

// What PassContext forwards to: one per pass instance.
struct PassContextImpl {
    Executor* exec = nullptr;
    int index = 0;
    Params params;
    std::vector<std::string> shader_dirs;
    std::map<std::string, std::unique_ptr<ShaderProgram>> programs;
    // Binding by declaration, each kind in its own range from 0 (pathlet/gl_limits.hpp): a texture
    // pin read as a sampler gets a texture unit, one read as an image an image unit, both on first
    // sight in a program of the pass; other samplers and images of the pass's programs the next
    // ones. Buffer pins get storage binding points in declaration order (<PIN>_BINDING in GLSL).
    std::map<std::string, int> sampler_unit, image_unit, buffer_binding;
    int samplers = 0, images = 0;
    std::set<std::string> sampled_pins, image_pins;
    std::map<std::pair<std::string, GLenum>, BufferTexture> buffer_views;  // buffer_texture()

    const CompiledPass& pass() const { return exec->cg_.passes[size_t(index)]; }
    const Binding* binding(const std::string& pin) const {
        const auto& b = pass().bindings;
        auto it = b.find(pin);
        return it == b.end() || it->second.resource < 0 ? nullptr : &it->second;
    }
    [[noreturn]] void unbound(const std::string& pin, const char* what) const {
        throw PassError("pass '" + pass().name + "' (" + pass().type->type + ") asked for " + what + " pin '" + pin +
                        "', which is not connected" +
                        (pass().type->pin(pin) ? "" : " (the pass type declares no such pin)"));
    }
};

// ---- PassContext (the pass's view) -------------------------------------------------------

const std::string& PassContext::pass_name() const { return impl_->pass().name; }
const Params& PassContext::params() const { return impl_->params; }
glm::ivec2 PassContext::output_size() const { return impl_->exec->cg_.output_size; }
float PassContext::pixel_scale() const { return impl_->exec->cg_.pixel_scale; }
bool PassContext::connected(const std::string& pin) const { return impl_->binding(pin) != nullptr; }

Texture PassContext::texture(const std::string& pin) const {
    const Binding* b = impl_->binding(pin);
    if (!b) impl_->unbound(pin, "texture");
    const auto& ph = impl_->exec->physical(b->resource, b->previous);
    if (!ph.tex) impl_->unbound(pin, "texture (it is bound to a buffer)");
    return ph.tex;
}

Buffer PassContext::buffer(const std::string& pin) const {
    const Binding* b = impl_->binding(pin);
    if (!b) impl_->unbound(pin, "buffer");
    const auto& ph = impl_->exec->physical(b->resource, b->previous);
    if (!ph.buf) impl_->unbound(pin, "buffer (it is bound to a texture)");
    return ph.buf;
}

Buffer PassContext::grow_buffer(const std::string& pin, size_t bytes) {
    const Binding* b = impl_->binding(pin);
    if (!b) impl_->unbound(pin, "buffer");
    if (b->previous) throw PassError("pass '" + impl_->pass().name + "' cannot grow last frame's '" + pin + "'");
    auto& ph = const_cast<Executor::Physical&>(impl_->exec->physical(b->resource, false));
    if (!ph.buf) impl_->unbound(pin, "buffer (it is bound to a texture)");
    if (ph.buf.bytes >= bytes) return ph.buf;
    // A new, larger store: GL buffer storage is immutable. The content is not kept (a pass
    // grows a buffer it is about to refill); every pass that reads it sees the new one.
    GLuint id = 0;
    glCreateBuffers(1, &id);
    glNamedBufferStorage(id, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
    std::string label = impl_->exec->cg_.resources[size_t(b->resource)].name + " (grown)";
    glObjectLabel(GL_BUFFER, id, -1, label.c_str());
    glDeleteBuffers(1, &ph.buf.id);
    ph.buf = {id, bytes};
    // The pin's binding point now holds the new store (bind_pins bound the old one).
    auto at = impl_->buffer_binding.find(pin);
    if (at != impl_->buffer_binding.end()) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(at->second), id);
    return ph.buf;
}

const GpuScene& PassContext::scene() const { return impl_->exec->scene_; }

ShaderProgram& PassContext::program(const std::vector<std::string>& files, const std::vector<std::string>& defines) {
    std::string key;
    for (const auto& f : files) key += f + "|";
    key += "#";
    for (const auto& d : defines) key += d + "|";
    auto& slot = impl_->programs[key];
    if (!slot) {
        std::vector<std::string> all = defines;
        for (const auto& [pin, binding] : impl_->buffer_binding) all.push_back(binding_define(pin) + " " + std::to_string(binding));
        auto prog = std::make_unique<ShaderProgram>(ShaderProgram::from_files(files, impl_->shader_dirs, all));
        for (const auto& u : std::vector<ShaderProgram::Uniform>(prog->uniforms())) {
            if (!u.opaque) continue;
            const std::string pin = u.name.rfind("u_", 0) == 0 ? u.name.substr(2) : "";
            const PinDecl* decl = pin.empty() ? nullptr : impl_->pass().type->pin(pin);
            const bool is_pin = decl && decl->kind == PinKind::Texture;
            std::map<std::string, int>& units = u.image ? impl_->image_unit : impl_->sampler_unit;
            int unit = 0;
            if (is_pin && units.count(pin)) {
                unit = units[pin];
            } else {
                unit = impl_->exec->take_units(*impl_, u.image, u.size, u.name);
                if (is_pin) units[pin] = unit;
            }
            if (is_pin) (u.image ? impl_->image_pins : impl_->sampled_pins).insert(pin);
            prog->set_unit(u.name, unit);
        }
        // Uniform blocks keep the program's own numbering from 0 (ShaderProgram::block_binding).
        impl_->exec->max_blocks_ = std::max(impl_->exec->max_blocks_, int(prog->uniform_blocks().size()));
        bind_params(*prog);
        slot = std::move(prog);
    }
    return *slot;
}

int PassContext::buffer_binding(const std::string& pin) const {
    auto it = impl_->buffer_binding.find(pin);
    if (it == impl_->buffer_binding.end())
        throw PassError("pass '" + impl_->pass().name + "' asked for the binding point of '" + pin +
                        "', which is not one of its buffer pins");
    return it->second;
}

namespace {
// "graph.json:/passes/3: " for an error of a pass (the graph file and the pass's place in it),
// so a setup error names the file and the place like the compiler's errors do.
std::string where(const CompiledGraph& g, const CompiledPass& p) {
    if (g.file.empty()) return p.pointer.empty() ? "" : p.pointer + ": ";
    return g.file + ":" + p.pointer + ": ";
}
const char* glsl_type_name(GLenum t) {
    switch (t) {
        case GL_FLOAT: return "float";
        case GL_FLOAT_VEC2: return "vec2";
        case GL_FLOAT_VEC3: return "vec3";
        case GL_FLOAT_VEC4: return "vec4";
        case GL_INT: return "int";
        case GL_INT_VEC2: return "ivec2";
        case GL_UNSIGNED_INT: return "uint";
        case GL_BOOL: return "bool";
        case GL_FLOAT_MAT4: return "mat4";
        default: return "another type";
    }
}
}  // namespace

void PassContext::bind_params(const ShaderProgram& prog) const {
    const PassTypeInfo* type = impl_->pass().type;
    const float scale = pixel_scale();
    for (const ParamDecl& d : type->params) {
        if (d.type == ParamType::String) continue;
        const ShaderProgram::Uniform* u = prog.uniform("u_" + d.name);
        if (!u || u->opaque) continue;
        const json& v = impl_->params.raw().at(d.name);
        const GLuint id = prog.id();
        bool fits = true;
        switch (d.type) {
            case ParamType::Bool:
                fits = u->type == GL_BOOL || u->type == GL_INT;
                if (fits) glProgramUniform1i(id, u->location, v.get<bool>() ? 1 : 0);
                break;
            case ParamType::Int: {
                const double x = v.get<double>() * (d.pixels ? scale : 1.0f);
                if (u->type == GL_INT || u->type == GL_BOOL) glProgramUniform1i(id, u->location, int(std::lround(x)));
                else if (u->type == GL_UNSIGNED_INT) glProgramUniform1ui(id, u->location, GLuint(std::llround(std::max(x, 0.0))));
                else if (u->type == GL_FLOAT) glProgramUniform1f(id, u->location, float(x));
                else fits = false;
                break;
            }
            case ParamType::Float:
                fits = u->type == GL_FLOAT;
                if (fits) glProgramUniform1f(id, u->location, float(v.get<double>() * (d.pixels ? scale : 1.0f)));
                break;
            case ParamType::Enum:
                fits = u->type == GL_INT;
                if (fits) glProgramUniform1i(id, u->location, impl_->params.index(d.name));
                break;
            case ParamType::Vec3:
            case ParamType::Color:
                fits = u->type == GL_FLOAT_VEC3;
                if (fits) glProgramUniform3f(id, u->location, v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
                break;
            case ParamType::String: break;
        }
        if (!fits)
            throw ShaderError("uniform 'u_" + d.name + "' is " + glsl_type_name(u->type) + " in the program, but parameter '" +
                              d.name + "' is " + to_string(d.type) +
                              " (declared parameters reach u_<name>: rename the uniform or fix its type)");
    }
}

GLuint PassContext::buffer_texture(const std::string& pin, GLenum format) {
    return impl_->buffer_views[{pin, format}].of(buffer(pin), format);
}

void PassContext::bind_framebuffer(const std::vector<std::string>& color_pins, const std::string& depth_pin, int mip) {
    std::vector<GLuint> color;
    int w = 0, h = 0;
    auto take_size = [&](const Texture& t) {
        w = std::max(1, t.width >> mip);
        h = std::max(1, t.height >> mip);
    };
    for (const auto& p : color_pins) {
        Texture t = texture(p);
        color.push_back(t.id);
        take_size(t);
    }
    GLuint depth = 0;
    if (!depth_pin.empty()) {
        Texture t = texture(depth_pin);
        depth = t.id;
        take_size(t);
    }
    if (color.empty() && !depth) {  // no attachments: the raster has the output's size
        w = std::max(1, output_size().x >> mip);
        h = std::max(1, output_size().y >> mip);
    }
    GLuint fbo = impl_->exec->framebuffer(color, depth, mip, impl_->pass().name);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
}

std::string PassContext::write_image(const std::string& pin, const std::string& pattern) {
    // Through the render's output side: a pixel-pack copy now, encoded on a writer thread, the
    // file renamed into place once whole (Executor::finish() or the destructor waits for it).
    AsyncOutput::Capture c;
    c.what = "pass '" + pass_name() + "' input '" + pin + "'";
    c.tex = texture(pin);
    c.file = expand_pattern(pattern, {{"pass", pass_name()}}, frame_index());
    ensure_parent_dir(c.file);
    Executor& e = *impl_->exec;
    if (!e.pass_output_) e.pass_output_ = std::make_unique<AsyncOutput>(AsyncOutput::Options{});
    e.pass_output_->capture({c});
    return c.file;
}

uint64_t PassContext::frame_index() const { return impl_->exec->frame_.index; }
double PassContext::time() const { return impl_->exec->frame_.time; }
const Camera& PassContext::camera() const { return impl_->exec->frame_.camera; }

void PassContext::frame_incomplete(uint64_t frame) { impl_->exec->incomplete_.insert(frame); }

void PassContext::stat(const std::string& name, double value) {
    if (impl_->exec->profiler_) impl_->exec->profiler_->add_stat(impl_->pass().name, name, value);
}

void PassContext::draw_fullscreen() {
    glBindVertexArray(impl_->exec->empty_vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}

void PassContext::draw_fullscreen_on_geometry(ShaderProgram& prog) {
    prog.use();
    prog.set("u_fullscreen_z", 1.0f);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);  // 1.0 > stored depth: geometry only
    glDepthMask(GL_FALSE);    // the depth texture stays read-only
    draw_fullscreen();
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
    prog.set("u_fullscreen_z", 0.0f);
}

// ---- Executor -----------------------------------------------------------------------------

Executor::Executor(GlContext& gl, const CompiledGraph& cg, const GpuScene& scene, Profiler* profiler)
    : gl_(gl), cg_(cg), scene_(scene), profiler_(profiler) {}

Executor::~Executor() {
    if (pass_output_) {  // what passes asked to write is written (a destructor cannot throw: told)
        try {
            pass_output_->finish();
        } catch (const std::exception& e) {
            std::fprintf(stderr, "error: %s\n", e.what());
        }
        pass_output_.reset();
    }
    passes_.clear();  // pass destructors may delete their own GL objects
    contexts_.clear();
    for (auto& [k, fbo] : fbos_) glDeleteFramebuffers(1, &fbo);
    auto free_phys = [](Physical& p) {
        if (p.tex.id) glDeleteTextures(1, &p.tex.id);
        if (p.buf.id) glDeleteBuffers(1, &p.buf.id);
    };
    for (auto& p : slots_) free_phys(p);
    for (auto& [r, p] : history_prev_) free_phys(p);
    if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
}

std::vector<std::string> Executor::shader_dirs_for(const PassTypeInfo& type) const {
    return shader_search_path(type, cg_.dirs);
}

namespace {
// What a pass sees: its parameters with each hook file as the compiler found it (a hook next
// to the graph before a shipped one of the same name), and that file on its shader path.
Params pass_params(const CompiledPass& cp) {
    json params = cp.params;
    for (const auto& h : cp.hooks)
        if (params.value(h.param, "") == h.name) params[h.param] = h.file;
    return Params(cp.name, params, cp.type);
}
void add_hook_files(const CompiledPass& cp, std::vector<std::string>& dirs) {
    for (const auto& h : cp.hooks) dirs.push_back(h.file);
}
}  // namespace

Executor::Physical Executor::make_physical(const PoolSlot& s, const std::string& full_label) {
    Physical p;
    // GL_MAX_LABEL_LENGTH is 256 on Mesa; long pooled labels ("a+b+c...") are cut.
    std::string label = full_label.size() > 200 ? full_label.substr(0, 197) + "..." : full_label;
    if (s.kind == PinKind::Texture) {
        const FormatInfo* fi = find_format(s.internal_format);
        glCreateTextures(GL_TEXTURE_2D, 1, &p.tex.id);
        glTextureStorage2D(p.tex.id, std::max(1, s.mips), s.internal_format, s.width, s.height);
        bool filterable = fi && !fi->is_integer && !fi->depth;
        GLenum min = filterable ? (s.mips > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR) : GL_NEAREST;
        glTextureParameteri(p.tex.id, GL_TEXTURE_MIN_FILTER, GLint(min));
        glTextureParameteri(p.tex.id, GL_TEXTURE_MAG_FILTER, filterable ? GL_LINEAR : GL_NEAREST);
        glTextureParameteri(p.tex.id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(p.tex.id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glObjectLabel(GL_TEXTURE, p.tex.id, -1, label.c_str());
        p.tex.width = s.width;
        p.tex.height = s.height;
        p.tex.mips = std::max(1, s.mips);
        p.tex.internal_format = s.internal_format;
    } else {
        glCreateBuffers(1, &p.buf.id);
        glNamedBufferStorage(p.buf.id, GLsizeiptr(std::max<size_t>(s.bytes, 4)), nullptr, GL_DYNAMIC_STORAGE_BIT);
        glObjectLabel(GL_BUFFER, p.buf.id, -1, label.c_str());
        p.buf.bytes = s.bytes;
    }
    return p;
}

const Executor::Physical& Executor::physical(int resource, bool previous) const {
    if (previous) {
        auto it = history_prev_.find(resource);
        if (it != history_prev_.end()) return it->second;
    }
    return slots_.at(size_t(cg_.resources.at(size_t(resource)).slot));
}

GLuint Executor::framebuffer(const std::vector<GLuint>& color, GLuint depth, int mip, const std::string& pass) {
    std::vector<GLuint> key = color;
    key.push_back(depth);
    key.push_back(GLuint(mip));
    auto it = fbos_.find(key);
    if (it != fbos_.end()) return it->second;
    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    std::vector<GLenum> draw;
    for (size_t i = 0; i < color.size(); ++i) {
        glNamedFramebufferTexture(fbo, GLenum(GL_COLOR_ATTACHMENT0 + i), color[i], mip);
        draw.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
    }
    if (depth) glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth, mip);
    if (color.empty() && !depth) {
        glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH, std::max(1, cg_.output_size.x >> mip));
        glNamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT, std::max(1, cg_.output_size.y >> mip));
    }
    if (draw.empty())
        glNamedFramebufferDrawBuffer(fbo, GL_NONE);
    else
        glNamedFramebufferDrawBuffers(fbo, GLsizei(draw.size()), draw.data());
    GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        glDeleteFramebuffers(1, &fbo);
        std::ostringstream s;
        s << "pass '" << pass << "': framebuffer incomplete (status 0x" << std::hex << status
          << "); check that its outputs are colour-renderable formats of one size";
        throw PassError(s.str());
    }
    fbos_[key] = fbo;
    return fbo;
}

void Executor::check_gl(const std::string& pass, const char* phase) {
    auto errs = gl_.take_errors();
    if (errs.empty()) return;
    std::string msg = "pass '" + pass + "' caused OpenGL errors in " + phase + ":";
    for (const auto& e : errs) msg += "\n  " + e;
    throw PassError(msg);
}

void Executor::setup() {
    gl_.take_errors();  // start clean
    glCreateVertexArrays(1, &empty_vao_);
    slots_.clear();
    for (size_t i = 0; i < cg_.slots.size(); ++i) {
        std::string label;
        for (int r : cg_.slots[i].resources) label += (label.empty() ? "" : "+") + cg_.resources[size_t(r)].name;
        slots_.push_back(make_physical(cg_.slots[i], label));
    }
    for (size_t r = 0; r < cg_.resources.size(); ++r) {
        const auto& res = cg_.resources[r];
        if (!res.history || res.slot < 0) continue;
        Physical prev = make_physical(cg_.slots[size_t(res.slot)], res.name + "@prev");
        // Frame 0 reads an empty history: zero it so it is defined.
        if (prev.tex) {
            // The clear's pixel format must match the texture's kind (integer formats such as r32i).
            const FormatInfo* fi = find_format(prev.tex.internal_format);
            const GLenum fmt = fi ? fi->pixel_format : GL_RGBA, type = fi ? fi->pixel_type : GL_FLOAT;
            for (int m = 0; m < prev.tex.mips; ++m) glClearTexImage(prev.tex.id, m, fmt, type, nullptr);
        } else {
            glClearNamedBufferData(prev.buf.id, GL_R8, GL_RED, GL_UNSIGNED_BYTE, nullptr);
        }
        history_prev_[int(r)] = prev;
    }
    check_gl("(engine)", "resource creation");

    passes_.clear();
    contexts_.clear();
    gpu_waits_.reset(cg_.passes.size());
    for (size_t i = 0; i < cg_.passes.size(); ++i) {
        const CompiledPass& cp = cg_.passes[i];
        auto impl = std::make_unique<PassContextImpl>();
        impl->exec = this;
        impl->index = int(i);
        impl->params = pass_params(cp);
        impl->shader_dirs = shader_dirs_for(*cp.type);
        add_hook_files(cp, impl->shader_dirs);
        for (const PinDecl& pin : cp.type->pins)
            if (pin.kind == PinKind::Buffer) impl->buffer_binding.emplace(pin.name, int(impl->buffer_binding.size()));
        std::unique_ptr<Pass> pass;
        gl_.set_scope(cp.name);
        try {
            const GlLimits& limits = gl_limits();
            const int bindings = limits.get(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS);
            if (int(impl->buffer_binding.size()) > bindings)
                throw PassError("its " + std::to_string(impl->buffer_binding.size()) +
                                " buffer pins need as many storage-buffer binding points; this context has " +
                                std::to_string(bindings) + limits.source(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS));
            max_bindings_ = std::max(max_bindings_, int(impl->buffer_binding.size()));
            pass = cp.type->create();
            if (!pass) throw PassError("its factory returned nothing");
            PassContext ctx(impl.get());
            reset_gl_state();
            pass->setup(ctx);
        } catch (const ShaderError& e) {
            gl_.take_errors();  // the compile's own debug messages: reported here, not by the next frame
            throw PassError(where(cg_, cp) + "pass '" + cp.name + "' (" + cp.type->type + "): " + e.what());
        } catch (const std::exception& e) {
            gl_.take_errors();
            throw PassError(where(cg_, cp) + "pass '" + cp.name + "' (" + cp.type->type + ") failed in setup: " + e.what());
        } catch (...) {
            gl_.take_errors();
            throw PassError(where(cg_, cp) + "pass '" + cp.name + "' (" + cp.type->type + ") threw a non-standard exception in setup");
        }
        check_gl(cp.name, "setup");
        passes_.push_back(std::move(pass));
        contexts_.push_back(std::move(impl));
    }
    gl_.set_scope("");
}

void Executor::reparam(size_t i) {
    if (i >= passes_.size()) throw PassError("reparam: no pass " + std::to_string(i));
    const CompiledPass& cp = cg_.passes[i];
    PassContextImpl& impl = *contexts_[i];
    Params old = impl.params;
    impl.params = pass_params(cp);
    gpu_waits_.set_up(i);
    gl_.set_scope(cp.name);
    // The programs the pass has get the new parameters first; setup() then sets what it derives.
    auto set_up = [&] {
        PassContext ctx(&impl);
        for (const auto& [key, prog] : impl.programs) ctx.bind_params(*prog);
        reset_gl_state();
        passes_[i]->setup(ctx);
    };
    try {
        set_up();
    } catch (const std::exception& e) {
        gl_.take_errors();  // the failed setup's own messages
        impl.params = old;  // back to what worked, set up again
        try {
            set_up();
        } catch (...) {
        }
        gl_.set_scope("");
        throw PassError(where(cg_, cp) + "pass '" + cp.name + "' (" + cp.type->type + ") failed in setup: " + e.what());
    }
    check_gl(cp.name, "setup");
    gl_.set_scope("");
}

void Executor::run_frame(const FrameInfo& f) {
    frame_ = f;
    advance_gpu_frame();  // the frame clock of pathlet/gpu_fence.hpp
    frames_in_flight_.begin_frame();
    // Debug groups cost a message round trip per pass on Mesa; only with PATHLET_GL_DEBUG.
    static const bool groups = std::getenv("PATHLET_GL_DEBUG") != nullptr;
    if (profiler_) profiler_->begin_frame(f.index);
    for (size_t i = 0; i < passes_.size(); ++i) {
        const CompiledPass& cp = cg_.passes[i];
        gl_.set_scope(cp.name);
        if (groups) glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, GLuint(i), -1, cp.name.c_str());
        if (profiler_) profiler_->begin_pass(cp.name);
        try {
            PassContext ctx(contexts_[i].get());
            reset_gl_state();
            bind_pins(*contexts_[i]);
            GpuWaitCounter::Scope waits(gpu_waits_, i, f.index);  // the pass's own waits, under the mode
            passes_[i]->execute(ctx);
        } catch (const std::exception& e) {
            if (groups) glPopDebugGroup();
            gl_.set_scope("");
            throw PassError("pass '" + cp.name + "' (" + cp.type->type + ") failed in frame " +
                            std::to_string(f.index) + ": " + e.what());
        } catch (...) {
            if (groups) glPopDebugGroup();
            gl_.set_scope("");
            throw PassError("pass '" + cp.name + "' (" + cp.type->type + ") threw a non-standard exception");
        }
        if (profiler_) profiler_->end_pass();
        if (groups) glPopDebugGroup();
        // The debug callback flags errors as they happen, so this check costs nothing when all
        // is well. glGetError (a round trip to a threaded driver) only with PATHLET_GL_DEBUG,
        // after every pass; without it, errors no callback reported are caught at the end of
        // the run (finish()). docs/performance.md.
        if (groups || gl_.has_errors()) check_gl(cp.name, "execute");
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    // A driver that reports from its own thread may flag an error after its pass's check.
    if (gl_.has_errors()) check_gl("(one of this frame's passes; PATHLET_GL_DEBUG=1 narrows it down)", "execute");
    gl_.set_scope("");
    if (pass_output_) pass_output_->poll();  // capture passes: what the GPU has copied goes to the writers
    if (profiler_) profiler_->end_frame();
    frames_in_flight_.end_frame();
    // History: what was written this frame becomes next frame's @prev.
    for (auto& [r, prev] : history_prev_) std::swap(prev, slots_[size_t(cg_.resources[size_t(r)].slot)]);
}

void Executor::finish() {
    for (size_t i = 0; i < passes_.size(); ++i) {
        const CompiledPass& cp = cg_.passes[i];
        try {
            PassContext ctx(contexts_[i].get());
            passes_[i]->finish(ctx);
        } catch (const std::exception& e) {
            throw PassError("pass '" + cp.name + "' (" + cp.type->type + ") failed at the end of the run: " + e.what());
        }
    }
    if (pass_output_) pass_output_->finish();  // the capture passes' files
    for (size_t i = 0; i < passes_.size() && gpu_wait_counting(); ++i)
        if (const std::string line = gpu_wait_line(cg_.passes[i].name, *cg_.passes[i].type, contexts_[i]->params,
                                                   gpu_waits_.counts()[i]); !line.empty())
            std::fprintf(stderr, "%s\n", line.c_str());
    // Errors no debug callback reported: glGetError is not asked per frame (docs/performance.md).
    check_gl("(one of the run's passes; PATHLET_GL_DEBUG=1 narrows it down)", "the run");
}

// The documented state every pass starts from (pass.hpp): whatever the previous pass changed.
void Executor::reset_gl_state() {
    glUseProgram(0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, cg_.output_size.x, cg_.output_size.y);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBlendFunc(GL_ONE, GL_ZERO);
    // Whatever units and binding points any pass was given (none beyond the context's limits).
    if (max_samplers_) glBindTextures(0, max_samplers_, nullptr);
    if (max_images_) glBindImageTextures(0, max_images_, nullptr);
    if (max_bindings_) glBindBuffersBase(GL_SHADER_STORAGE_BUFFER, 0, max_bindings_, nullptr);
    if (max_blocks_) glBindBuffersBase(GL_UNIFORM_BUFFER, 0, max_blocks_, nullptr);
}

// The next `count` sampler or image units of a pass, within the context's limits.
int Executor::take_units(PassContextImpl& impl, bool image, int count, const std::string& uniform) {
    const GlLimits& limits = gl_limits();
    const GLenum limit = image ? GL_MAX_IMAGE_UNITS : GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS;
    int& next = image ? impl.images : impl.samplers;
    const int first = next;
    next += std::max(count, 1);
    if (next > limits.get(limit))
        throw PassError(std::string("'") + uniform + "' needs " + (image ? "image" : "texture") + " unit " +
                        std::to_string(next - 1) + " (" + std::to_string(next) + " " + (image ? "images" : "samplers") +
                        " in the pass's programs); this context has " + std::to_string(limits.get(limit)) +
                        (image ? " image units" : " texture units") + limits.source(limit));
    int& max = image ? max_images_ : max_samplers_;
    max = std::max(max, next);
    return first;
}

// Texture pins that a program of the pass reads as u_<pin>, on the pin's unit; buffer pins on
// their storage binding points.
void Executor::bind_pins(const PassContextImpl& impl) {
    PassContext ctx(const_cast<PassContextImpl*>(&impl));
    for (const std::string& pin : impl.sampled_pins)
        glBindTextureUnit(GLuint(impl.sampler_unit.at(pin)), ctx.connected(pin) ? ctx.texture(pin).id : 0);
    for (const std::string& pin : impl.image_pins)
        if (ctx.connected(pin)) {
            const Texture t = ctx.texture(pin);
            glBindImageTexture(GLuint(impl.image_unit.at(pin)), t.id, 0, GL_FALSE, 0, GL_READ_WRITE, t.internal_format);
        }
    for (const auto& [pin, binding] : impl.buffer_binding)
        if (ctx.connected(pin)) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(binding), ctx.buffer(pin).id);
}

Texture Executor::texture(const std::string& resource) const {
    int r = cg_.find_resource(resource);
    if (r < 0) throw PassError("no resource named '" + resource + "' in the compiled graph");
    // After the swap, the frame's content of a history resource lives in history_prev_.
    const Physical& p = cg_.resources[size_t(r)].history ? physical(r, true) : physical(r, false);
    return p.tex;
}

Buffer Executor::buffer(const std::string& resource) const {
    int r = cg_.find_resource(resource);
    if (r < 0) throw PassError("no resource named '" + resource + "' in the compiled graph");
    const Physical& p = cg_.resources[size_t(r)].history ? physical(r, true) : physical(r, false);
    return p.buf;
}

}  // namespace pathlet
