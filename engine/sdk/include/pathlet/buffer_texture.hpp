// A buffer seen as a buffer texture (samplerBuffer / imageBuffer), for a stage that may not have
// storage blocks (GL 4.5 guarantees vertex and geometry shaders none) or for image load/store on
// a buffer. A buffer that grows is a new GL object: of() makes a new view whenever the buffer it
// is given is another one (its id or its size changed). A pass asks its context instead
// (PassContext::buffer_texture), which owns the view.
#pragma once

#include <pathlet/gl.hpp>
#include <pathlet/pass.hpp>

namespace pathlet {

class BufferTexture {
public:
    BufferTexture() = default;
    BufferTexture(const BufferTexture&) = delete;
    BufferTexture& operator=(const BufferTexture&) = delete;
    BufferTexture(BufferTexture&& o) noexcept : view_(o.view_), of_(o.of_), format_(o.format_) { o.view_ = 0; }
    ~BufferTexture() {
        if (view_) glDeleteTextures(1, &view_);
    }
    // The view of `b` with texel format `format` (GL_RGBA32UI, GL_RGBA32F, GL_R32F, ...).
    GLuint of(const Buffer& b, GLenum format) {
        if (b.id != of_.id || b.bytes != of_.bytes || format != format_) {
            if (view_) glDeleteTextures(1, &view_);
            glCreateTextures(GL_TEXTURE_BUFFER, 1, &view_);
            glTextureBuffer(view_, format, b.id);
            of_ = b;
            format_ = format;
        }
        return view_;
    }

private:
    GLuint view_ = 0;
    Buffer of_;
    GLenum format_ = 0;
};

}  // namespace pathlet
