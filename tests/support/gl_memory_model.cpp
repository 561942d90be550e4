#include "gl_memory_model.hpp"

#include <pathlet/gl.hpp>

#include <dlfcn.h>

#include <cstdlib>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>
#include <tuple>

namespace pathlet::gl_memory_model {
namespace {

// What a draw or dispatch may have written and who has flushed it since.
struct Written {
    std::string writer;
    std::set<std::string> flushed_by;  // passes that issued the update barrier since the write
};

struct State {
    std::mutex m;
    std::string pass;  // the innermost debug group: the executor's pass name
    std::vector<std::string> groups;
    std::map<GLuint, std::pair<GLuint, GLenum>> image_units;  // unit -> texture, access
    std::map<GLuint, GLuint> storage_bindings;                // binding -> buffer
    std::map<GLuint, GLuint> texture_buffers;                 // buffer texture -> its buffer
    std::map<GLuint, Written> textures, buffers;
    std::map<std::tuple<std::string, std::string, std::string>, size_t> violations;  // pass, call, writer
    std::map<std::tuple<std::string, std::string, std::string>, std::string> example;
    bool fail_maps = false;
    bool seen = false;  // an interposed call ran
};

State& state() {
    static State s;
    return s;
}

// The driver's entry point behind ours.
template <class F>
F real(const char* name) {
    void* p = dlsym(RTLD_NEXT, name);
    if (!p) throw std::runtime_error(std::string("gl_memory_model: no driver entry point ") + name);
    return reinterpret_cast<F>(p);
}
#define PATHLET_REAL(name) static const auto real_##name = real<decltype(&::name)>(#name)

// A draw or dispatch: everything bound for shader writes may now hold unflushed writes.
void shader_ran() {
    State& s = state();
    std::lock_guard lock(s.m);
    s.seen = true;
    for (const auto& [unit, bound] : s.image_units) {
        if (bound.second == GL_READ_ONLY) continue;
        if (auto b = s.texture_buffers.find(bound.first); b != s.texture_buffers.end())
            s.buffers[b->second] = {s.pass, {}};
        else
            s.textures[bound.first] = {s.pass, {}};
    }
    for (const auto& [binding, buffer] : s.storage_bindings) s.buffers[buffer] = {s.pass, {}};
}

void updated(std::map<GLuint, Written>& written, GLuint name, const char* call, const char* kind) {
    State& s = state();
    auto it = written.find(name);
    if (it == written.end()) return;
    const Written& w = it->second;
    if (w.flushed_by.count(w.writer) || w.flushed_by.count(s.pass)) {
        written.erase(it);  // flushed: the update is ordered after the writes
        return;
    }
    const auto key = std::make_tuple(s.pass, std::string(call), w.writer);
    if (s.violations[key]++ == 0) s.example[key] = std::string(kind) + " " + std::to_string(name);
    written.erase(it);
}

void texture_updated(GLuint texture, const char* call) {
    std::lock_guard lock(state().m);
    state().seen = true;
    updated(state().textures, texture, call, "texture");
}
void buffer_updated(GLuint buffer, const char* call) {
    std::lock_guard lock(state().m);
    state().seen = true;
    updated(state().buffers, buffer, call, "buffer");
}

// Run at load: the executor names its passes in debug groups only with PATHLET_GL_DEBUG.
[[maybe_unused]] const bool debug_groups_on = [] {
    ::setenv("PATHLET_GL_DEBUG", "1", 0);
    return true;
}();

}  // namespace

std::string Violation::str() const {
    return "pass '" + pass + "': " + call + " of " + resource + " after pass '" + writer +
           "' had it bound for shader writes, without an update barrier by either in between";
}

void reset() {
    State& s = state();
    std::lock_guard lock(s.m);
    s.textures.clear();
    s.buffers.clear();
    s.violations.clear();
    s.example.clear();
}

std::vector<std::string> take_violations() {
    State& s = state();
    std::lock_guard lock(s.m);
    std::vector<std::string> out;
    for (const auto& [key, n] : s.violations) {
        const Violation v{std::get<0>(key), std::get<1>(key), s.example[key], std::get<2>(key)};
        out.push_back(v.str() + (n > 1 ? " (" + std::to_string(n) + " times)" : ""));
    }
    s.violations.clear();
    s.example.clear();
    return out;
}

bool active() {
    State& s = state();
    std::lock_guard lock(s.m);
    return s.seen;
}

void fail_buffer_maps(bool on) {
    std::lock_guard lock(state().m);
    state().fail_maps = on;
}

}  // namespace pathlet::gl_memory_model

using namespace pathlet::gl_memory_model;

// ---- the interposed entry points: recorded, then forwarded ----------------------------------

extern "C" {

void APIENTRY glPushDebugGroup(GLenum source, GLuint id, GLsizei length, const GLchar* message) {
    PATHLET_REAL(glPushDebugGroup);
    {
        State& s = state();
        std::lock_guard lock(s.m);
        s.groups.push_back(length < 0 ? std::string(message) : std::string(message, size_t(length)));
        s.pass = s.groups.back();
    }
    real_glPushDebugGroup(source, id, length, message);
}
void APIENTRY glPopDebugGroup() {
    PATHLET_REAL(glPopDebugGroup);
    {
        State& s = state();
        std::lock_guard lock(s.m);
        if (!s.groups.empty()) s.groups.pop_back();
        s.pass = s.groups.empty() ? "" : s.groups.back();
    }
    real_glPopDebugGroup();
}

void APIENTRY glBindImageTexture(GLuint unit, GLuint texture, GLint level, GLboolean layered, GLint layer, GLenum access,
                                 GLenum format) {
    PATHLET_REAL(glBindImageTexture);
    {
        std::lock_guard lock(state().m);
        if (texture) state().image_units[unit] = {texture, access};
        else state().image_units.erase(unit);
    }
    real_glBindImageTexture(unit, texture, level, layered, layer, access, format);
}
void APIENTRY glBindImageTextures(GLuint first, GLsizei count, const GLuint* textures) {
    PATHLET_REAL(glBindImageTextures);
    {
        std::lock_guard lock(state().m);
        for (GLsizei i = 0; i < count; ++i) {
            if (textures && textures[i]) state().image_units[first + GLuint(i)] = {textures[i], GL_READ_WRITE};
            else state().image_units.erase(first + GLuint(i));
        }
    }
    real_glBindImageTextures(first, count, textures);
}

namespace {
void bind_storage(GLenum target, GLuint index, GLuint buffer) {
    if (target != GL_SHADER_STORAGE_BUFFER && target != GL_ATOMIC_COUNTER_BUFFER) return;
    std::lock_guard lock(state().m);
    const GLuint key = index + (target == GL_ATOMIC_COUNTER_BUFFER ? 0x10000u : 0u);
    if (buffer) state().storage_bindings[key] = buffer;
    else state().storage_bindings.erase(key);
}
}  // namespace

void APIENTRY glBindBufferBase(GLenum target, GLuint index, GLuint buffer) {
    PATHLET_REAL(glBindBufferBase);
    bind_storage(target, index, buffer);
    real_glBindBufferBase(target, index, buffer);
}
void APIENTRY glBindBufferRange(GLenum target, GLuint index, GLuint buffer, GLintptr offset, GLsizeiptr size) {
    PATHLET_REAL(glBindBufferRange);
    bind_storage(target, index, buffer);
    real_glBindBufferRange(target, index, buffer, offset, size);
}
void APIENTRY glBindBuffersBase(GLenum target, GLuint first, GLsizei count, const GLuint* buffers) {
    PATHLET_REAL(glBindBuffersBase);
    for (GLsizei i = 0; i < count; ++i) bind_storage(target, first + GLuint(i), buffers ? buffers[i] : 0);
    real_glBindBuffersBase(target, first, count, buffers);
}
void APIENTRY glBindBuffersRange(GLenum target, GLuint first, GLsizei count, const GLuint* buffers,
                                 const GLintptr* offsets, const GLsizeiptr* sizes) {
    PATHLET_REAL(glBindBuffersRange);
    for (GLsizei i = 0; i < count; ++i) bind_storage(target, first + GLuint(i), buffers ? buffers[i] : 0);
    real_glBindBuffersRange(target, first, count, buffers, offsets, sizes);
}
void APIENTRY glTextureBuffer(GLuint texture, GLenum internalformat, GLuint buffer) {
    PATHLET_REAL(glTextureBuffer);
    {
        std::lock_guard lock(state().m);
        state().texture_buffers[texture] = buffer;
    }
    real_glTextureBuffer(texture, internalformat, buffer);
}
void APIENTRY glTextureBufferRange(GLuint texture, GLenum internalformat, GLuint buffer, GLintptr offset,
                                   GLsizeiptr size) {
    PATHLET_REAL(glTextureBufferRange);
    {
        std::lock_guard lock(state().m);
        state().texture_buffers[texture] = buffer;
    }
    real_glTextureBufferRange(texture, internalformat, buffer, offset, size);
}

void APIENTRY glDrawArrays(GLenum mode, GLint first, GLsizei count) {
    PATHLET_REAL(glDrawArrays);
    real_glDrawArrays(mode, first, count);
    shader_ran();
}
void APIENTRY glDrawElements(GLenum mode, GLsizei count, GLenum type, const void* indices) {
    PATHLET_REAL(glDrawElements);
    real_glDrawElements(mode, count, type, indices);
    shader_ran();
}
void APIENTRY glDrawElementsIndirect(GLenum mode, GLenum type, const void* indirect) {
    PATHLET_REAL(glDrawElementsIndirect);
    real_glDrawElementsIndirect(mode, type, indirect);
    shader_ran();
}
void APIENTRY glMultiDrawArrays(GLenum mode, const GLint* first, const GLsizei* count, GLsizei drawcount) {
    PATHLET_REAL(glMultiDrawArrays);
    real_glMultiDrawArrays(mode, first, count, drawcount);
    shader_ran();
}
void APIENTRY glMultiDrawElements(GLenum mode, const GLsizei* count, GLenum type, const void* const* indices,
                                  GLsizei drawcount) {
    PATHLET_REAL(glMultiDrawElements);
    real_glMultiDrawElements(mode, count, type, indices, drawcount);
    shader_ran();
}
void APIENTRY glDispatchCompute(GLuint x, GLuint y, GLuint z) {
    PATHLET_REAL(glDispatchCompute);
    real_glDispatchCompute(x, y, z);
    shader_ran();
}
void APIENTRY glDispatchComputeIndirect(GLintptr indirect) {
    PATHLET_REAL(glDispatchComputeIndirect);
    real_glDispatchComputeIndirect(indirect);
    shader_ran();
}

void APIENTRY glMemoryBarrier(GLbitfield barriers) {
    PATHLET_REAL(glMemoryBarrier);
    {
        State& s = state();
        std::lock_guard lock(s.m);
        if (barriers & GL_TEXTURE_UPDATE_BARRIER_BIT)
            for (auto& [t, w] : s.textures) w.flushed_by.insert(s.pass);
        if (barriers & GL_BUFFER_UPDATE_BARRIER_BIT)
            for (auto& [b, w] : s.buffers) w.flushed_by.insert(s.pass);
    }
    real_glMemoryBarrier(barriers);
}

void APIENTRY glClearTexImage(GLuint texture, GLint level, GLenum format, GLenum type, const void* data) {
    PATHLET_REAL(glClearTexImage);
    texture_updated(texture, "glClearTexImage");
    real_glClearTexImage(texture, level, format, type, data);
}
void APIENTRY glClearTexSubImage(GLuint texture, GLint level, GLint x, GLint y, GLint z, GLsizei w, GLsizei h,
                                 GLsizei d, GLenum format, GLenum type, const void* data) {
    PATHLET_REAL(glClearTexSubImage);
    texture_updated(texture, "glClearTexSubImage");
    real_glClearTexSubImage(texture, level, x, y, z, w, h, d, format, type, data);
}
void APIENTRY glClearNamedBufferData(GLuint buffer, GLenum internalformat, GLenum format, GLenum type,
                                     const void* data) {
    PATHLET_REAL(glClearNamedBufferData);
    buffer_updated(buffer, "glClearNamedBufferData");
    real_glClearNamedBufferData(buffer, internalformat, format, type, data);
}
void APIENTRY glClearNamedBufferSubData(GLuint buffer, GLenum internalformat, GLintptr offset, GLsizeiptr size,
                                        GLenum format, GLenum type, const void* data) {
    PATHLET_REAL(glClearNamedBufferSubData);
    buffer_updated(buffer, "glClearNamedBufferSubData");
    real_glClearNamedBufferSubData(buffer, internalformat, offset, size, format, type, data);
}
void APIENTRY glNamedBufferSubData(GLuint buffer, GLintptr offset, GLsizeiptr size, const void* data) {
    PATHLET_REAL(glNamedBufferSubData);
    buffer_updated(buffer, "glNamedBufferSubData");
    real_glNamedBufferSubData(buffer, offset, size, data);
}

void* APIENTRY glMapNamedBufferRange(GLuint buffer, GLintptr offset, GLsizeiptr length, GLbitfield access) {
    PATHLET_REAL(glMapNamedBufferRange);
    {
        std::lock_guard lock(state().m);
        if (state().fail_maps) return nullptr;
    }
    return real_glMapNamedBufferRange(buffer, offset, length, access);
}

}  // extern "C"
