// The GL entry points that can wait for the GPU, defined in libpathlet so that calls from pass
// plugins and from libpathlet itself reach them before glvnd's libOpenGL (gpu_waits.hpp says
// why that holds and what counts). Each forwards to libOpenGL's entry point; while a pass is
// being counted on this thread it first notes a call that waits. Off the mode each costs one
// test of a thread-local pointer (and the query ones one of a flag) on top of the call.
#include "gpu_waits/gpu_waits.hpp"

#include <pathlet/gl.hpp>

#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <unordered_set>

#define PATHLET_GL_EXPORT extern "C" __attribute__((visibility("default")))

namespace {

// libOpenGL's definition of `name`: the next one after libpathlet in the search order, or, where
// libpathlet was found after libOpenGL (nothing follows it), libOpenGL's own.
void* resolve(const char* name) {
    void* f = dlsym(RTLD_NEXT, name);
    if (!f)
        if (void* gl = dlopen("libOpenGL.so.0", RTLD_LAZY | RTLD_NOLOAD)) f = dlsym(gl, name);
    if (!f) {
        std::fprintf(stderr, "pathlet: %s not found in libOpenGL (glvnd), which libpathlet forwards it to\n", name);
        std::abort();
    }
    return f;
}

#define PATHLET_REAL(name) static const auto real = reinterpret_cast<decltype(&::name)>(resolve(#name))

using pathlet::gpu_waits_detail::counting_here;
using pathlet::gpu_waits_detail::note;

bool bound(GLenum binding) {
    GLint id = 0;
    glGetIntegerv(binding, &id);
    return id != 0;
}

// Pixels read into client memory wait; into a bound pixel-pack buffer they are a GPU copy.
void note_pixels(const char* call) {
    if (counting_here() && !bound(GL_PIXEL_PACK_BUFFER_BINDING)) note(call);
}

// Queries whose GL_QUERY_RESULT_AVAILABLE was seen true since they were last issued (only
// while counting is on).
thread_local std::unordered_set<GLuint> t_available;

void issued(GLuint id) {
    if (pathlet::gpu_wait_counting()) t_available.erase(id);
}

// Around a glGetQueryObject*: before it, whether a result read waits; after it, what
// GL_QUERY_RESULT_AVAILABLE said. Into a bound query buffer neither applies (the GPU writes it).
void query_before(const char* call, GLuint id, GLenum pname) {
    if (pname == GL_QUERY_RESULT && counting_here() && !t_available.count(id) && !bound(GL_QUERY_BUFFER_BINDING))
        note(call);
}
template <class T>
void query_after(GLuint id, GLenum pname, const T* params) {
    if (pname == GL_QUERY_RESULT_AVAILABLE && pathlet::gpu_wait_counting() && !bound(GL_QUERY_BUFFER_BINDING) &&
        *params)
        t_available.insert(id);
}

bool read_map(GLenum access) { return access == GL_READ_ONLY || access == GL_READ_WRITE; }
bool read_map_synchronised(GLbitfield access) { return (access & GL_MAP_READ_BIT) && !(access & GL_MAP_PERSISTENT_BIT); }

}  // namespace

PATHLET_GL_EXPORT void APIENTRY glFinish(void) {
    PATHLET_REAL(glFinish);
    if (counting_here()) note("glFinish");
    real();
}

PATHLET_GL_EXPORT GLenum APIENTRY glClientWaitSync(GLsync sync, GLbitfield flags, GLuint64 timeout) {
    PATHLET_REAL(glClientWaitSync);
    if (timeout > 0 && counting_here()) note("glClientWaitSync");
    return real(sync, flags, timeout);
}

// ---- buffers ----------------------------------------------------------------------------------

PATHLET_GL_EXPORT void APIENTRY glGetBufferSubData(GLenum target, GLintptr offset, GLsizeiptr size, void* data) {
    PATHLET_REAL(glGetBufferSubData);
    if (counting_here()) note("glGetBufferSubData");
    real(target, offset, size, data);
}

PATHLET_GL_EXPORT void APIENTRY glGetNamedBufferSubData(GLuint buffer, GLintptr offset, GLsizeiptr size, void* data) {
    PATHLET_REAL(glGetNamedBufferSubData);
    if (counting_here()) note("glGetNamedBufferSubData");
    real(buffer, offset, size, data);
}

PATHLET_GL_EXPORT void* APIENTRY glMapBuffer(GLenum target, GLenum access) {
    PATHLET_REAL(glMapBuffer);
    if (read_map(access) && counting_here()) note("glMapBuffer");
    return real(target, access);
}

PATHLET_GL_EXPORT void* APIENTRY glMapNamedBuffer(GLuint buffer, GLenum access) {
    PATHLET_REAL(glMapNamedBuffer);
    if (read_map(access) && counting_here()) note("glMapNamedBuffer");
    return real(buffer, access);
}

PATHLET_GL_EXPORT void* APIENTRY glMapBufferRange(GLenum target, GLintptr offset, GLsizeiptr length, GLbitfield access) {
    PATHLET_REAL(glMapBufferRange);
    if (read_map_synchronised(access) && counting_here()) note("glMapBufferRange");
    return real(target, offset, length, access);
}

PATHLET_GL_EXPORT void* APIENTRY glMapNamedBufferRange(GLuint buffer, GLintptr offset, GLsizeiptr length,
                                                       GLbitfield access) {
    PATHLET_REAL(glMapNamedBufferRange);
    if (read_map_synchronised(access) && counting_here()) note("glMapNamedBufferRange");
    return real(buffer, offset, length, access);
}

// ---- pixels -----------------------------------------------------------------------------------

PATHLET_GL_EXPORT void APIENTRY glReadPixels(GLint x, GLint y, GLsizei width, GLsizei height, GLenum format,
                                             GLenum type, void* pixels) {
    PATHLET_REAL(glReadPixels);
    note_pixels("glReadPixels");
    real(x, y, width, height, format, type, pixels);
}

PATHLET_GL_EXPORT void APIENTRY glReadnPixels(GLint x, GLint y, GLsizei width, GLsizei height, GLenum format,
                                              GLenum type, GLsizei bufSize, void* data) {
    PATHLET_REAL(glReadnPixels);
    note_pixels("glReadnPixels");
    real(x, y, width, height, format, type, bufSize, data);
}

PATHLET_GL_EXPORT void APIENTRY glGetTexImage(GLenum target, GLint level, GLenum format, GLenum type, void* pixels) {
    PATHLET_REAL(glGetTexImage);
    note_pixels("glGetTexImage");
    real(target, level, format, type, pixels);
}

PATHLET_GL_EXPORT void APIENTRY glGetnTexImage(GLenum target, GLint level, GLenum format, GLenum type, GLsizei bufSize,
                                               void* pixels) {
    PATHLET_REAL(glGetnTexImage);
    note_pixels("glGetnTexImage");
    real(target, level, format, type, bufSize, pixels);
}

PATHLET_GL_EXPORT void APIENTRY glGetTextureImage(GLuint texture, GLint level, GLenum format, GLenum type,
                                                  GLsizei bufSize, void* pixels) {
    PATHLET_REAL(glGetTextureImage);
    note_pixels("glGetTextureImage");
    real(texture, level, format, type, bufSize, pixels);
}

PATHLET_GL_EXPORT void APIENTRY glGetTextureSubImage(GLuint texture, GLint level, GLint xoffset, GLint yoffset,
                                                     GLint zoffset, GLsizei width, GLsizei height, GLsizei depth,
                                                     GLenum format, GLenum type, GLsizei bufSize, void* pixels) {
    PATHLET_REAL(glGetTextureSubImage);
    note_pixels("glGetTextureSubImage");
    real(texture, level, xoffset, yoffset, zoffset, width, height, depth, format, type, bufSize, pixels);
}

PATHLET_GL_EXPORT void APIENTRY glGetCompressedTexImage(GLenum target, GLint level, void* img) {
    PATHLET_REAL(glGetCompressedTexImage);
    note_pixels("glGetCompressedTexImage");
    real(target, level, img);
}

PATHLET_GL_EXPORT void APIENTRY glGetnCompressedTexImage(GLenum target, GLint lod, GLsizei bufSize, void* pixels) {
    PATHLET_REAL(glGetnCompressedTexImage);
    note_pixels("glGetnCompressedTexImage");
    real(target, lod, bufSize, pixels);
}

PATHLET_GL_EXPORT void APIENTRY glGetCompressedTextureImage(GLuint texture, GLint level, GLsizei bufSize,
                                                            void* pixels) {
    PATHLET_REAL(glGetCompressedTextureImage);
    note_pixels("glGetCompressedTextureImage");
    real(texture, level, bufSize, pixels);
}

PATHLET_GL_EXPORT void APIENTRY glGetCompressedTextureSubImage(GLuint texture, GLint level, GLint xoffset,
                                                               GLint yoffset, GLint zoffset, GLsizei width,
                                                               GLsizei height, GLsizei depth, GLsizei bufSize,
                                                               void* pixels) {
    PATHLET_REAL(glGetCompressedTextureSubImage);
    note_pixels("glGetCompressedTextureSubImage");
    real(texture, level, xoffset, yoffset, zoffset, width, height, depth, bufSize, pixels);
}

// ---- queries ----------------------------------------------------------------------------------

PATHLET_GL_EXPORT void APIENTRY glBeginQuery(GLenum target, GLuint id) {
    PATHLET_REAL(glBeginQuery);
    issued(id);
    real(target, id);
}

PATHLET_GL_EXPORT void APIENTRY glBeginQueryIndexed(GLenum target, GLuint index, GLuint id) {
    PATHLET_REAL(glBeginQueryIndexed);
    issued(id);
    real(target, index, id);
}

PATHLET_GL_EXPORT void APIENTRY glQueryCounter(GLuint id, GLenum target) {
    PATHLET_REAL(glQueryCounter);
    issued(id);
    real(id, target);
}

#define PATHLET_QUERY_OBJECT(name, T)                                      \
    PATHLET_GL_EXPORT void APIENTRY name(GLuint id, GLenum pname, T* params) { \
        PATHLET_REAL(name);                                                \
        query_before(#name, id, pname);                                 \
        real(id, pname, params);                                           \
        query_after<T>(id, pname, params);                                 \
    }
PATHLET_QUERY_OBJECT(glGetQueryObjectiv, GLint)
PATHLET_QUERY_OBJECT(glGetQueryObjectuiv, GLuint)
PATHLET_QUERY_OBJECT(glGetQueryObjecti64v, GLint64)
PATHLET_QUERY_OBJECT(glGetQueryObjectui64v, GLuint64)
