#include "executor.hpp"

#include "formats.hpp"
#include "frames/async_output.hpp"
#include "gl_context.hpp"
#include "profiler/profiler.hpp"

#include <pathlet/gpu_fence.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace pathlet {

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

PassHost::Physical& Executor::physical(int resource, bool previous) {
    if (previous) {
        auto it = history_prev_.find(resource);
        if (it != history_prev_.end()) return it->second;
    }
    return slots_.at(size_t(cg_.resources.at(size_t(resource)).slot));
}

// What a resource holds after the frame: a history resource's content moved to last frame's slot.
const PassHost::Physical& Executor::current(int resource) const {
    if (cg_.resources[size_t(resource)].history) {
        auto it = history_prev_.find(resource);
        if (it != history_prev_.end()) return it->second;
    }
    return slots_.at(size_t(cg_.resources.at(size_t(resource)).slot));
}

void Executor::stat(const std::string& pass, const std::string& name, double value) {
    if (profiler_) profiler_->add_stat(pass, name, value);
}

AsyncOutput& Executor::pass_output() {
    if (!pass_output_) pass_output_ = std::make_unique<AsyncOutput>(AsyncOutput::Options{});
    return *pass_output_;
}

void Executor::used(const PassBindings& b, int uniform_blocks) {
    max_samplers_ = std::max(max_samplers_, b.samplers());
    max_images_ = std::max(max_images_, b.images());
    max_bindings_ = std::max(max_bindings_, int(b.buffers().size()));
    max_blocks_ = std::max(max_blocks_, uniform_blocks);
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
        PassHost& host = *this;
        auto impl = std::make_unique<PassContextImpl>(host, int(i), cp.shaders);
        std::unique_ptr<Pass> pass;
        gl_.set_scope(cp.name);
        try {
            impl->bindings = PassBindings(*cp.type, /*check_limits=*/true);
            used(impl->bindings, 0);
            pass = cp.type->create();
            if (!pass) throw PassError("its factory returned nothing");
            PassContext ctx(impl.get());
            reset_gl_state();
            pass->setup(ctx);
        } catch (const ShaderError& e) {
            gl_.take_errors();  // the compile's own debug messages: reported here, not by the next frame
            throw PassError(pass_label(cg_, cp) + ": " + e.what());
        } catch (const std::exception& e) {
            gl_.take_errors();
            throw PassError(pass_label(cg_, cp) + " failed in setup: " + e.what());
        } catch (...) {
            gl_.take_errors();
            throw PassError(pass_label(cg_, cp) + " threw a non-standard exception in setup");
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
    impl.take_params();
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
        throw PassError(pass_label(cg_, cp) + " failed in setup: " + e.what());
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
            contexts_[i]->bind_pins();
            GpuWaitCounter::Scope waits(gpu_waits_, i, f.index);  // the pass's own waits, under the mode
            passes_[i]->execute(ctx);
        } catch (const std::exception& e) {
            if (groups) glPopDebugGroup();
            gl_.set_scope("");
            throw PassError(pass_label(cg_, cp) + " failed in frame " + std::to_string(f.index) + ": " + e.what());
        } catch (...) {
            if (groups) glPopDebugGroup();
            gl_.set_scope("");
            throw PassError(pass_label(cg_, cp) + " threw a non-standard exception");
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
            throw PassError(pass_label(cg_, cp) + " failed at the end of the run: " + e.what());
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

Texture Executor::texture(const std::string& resource) const {
    int r = cg_.find_resource(resource);
    if (r < 0) throw PassError("no resource named '" + resource + "' in the compiled graph");
    return current(r).tex;
}

Buffer Executor::buffer(const std::string& resource) const {
    int r = cg_.find_resource(resource);
    if (r < 0) throw PassError("no resource named '" + resource + "' in the compiled graph");
    return current(r).buf;
}

}  // namespace pathlet
