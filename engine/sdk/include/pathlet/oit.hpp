// Order-independent transparency through per-pixel linked lists: the C++ side of the layout in
// shaders/oit_list.glsl, for clear_list, fill_list, resolve_list and any OIT pass of yours.
#pragma once

#include <pathlet/gl.hpp>
#include <pathlet/pass.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace pathlet::oit {

constexpr GLuint kEnd = 0xFFFFFFFFu;      // empty list / last node (OIT_END)
constexpr size_t kNodeBytes = 16;         // uvec4: colour, depth, next, line id
constexpr GLuint kCounterBinding = 8;     // OIT_COUNTER_BINDING: std430 { uint count; }

// The constants above for oit_list.glsl: add them to the defines of every program that
// includes it, so GLSL never repeats a number.
inline std::vector<std::string> defines() {
    return {"OIT_END " + std::to_string(kEnd) + "u", "OIT_COUNTER_BINDING " + std::to_string(kCounterBinding)};
}
// Empties every list: heads to kEnd, the node counter to 0.
inline void clear_lists(GLuint heads_texture, GLuint counter_buffer) {
    glClearTexImage(heads_texture, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &kEnd);
    const GLuint zero = 0;
    glClearNamedBufferData(counter_buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

// The nodes (or a per-node buffer beside them) as a buffer texture of uvec4 texels, for
// imageStore / texelFetch. fill_list grows the buffer on overflow, so of() makes a new view
// whenever the buffer it is given is another one (its id or its size changed).
class BufferView {
public:
    BufferView() = default;
    BufferView(const BufferView&) = delete;
    BufferView& operator=(const BufferView&) = delete;
    ~BufferView() {
        if (view_) glDeleteTextures(1, &view_);
    }
    GLuint of(const Buffer& b) {
        if (b.id != of_.id || b.bytes != of_.bytes) {
            if (view_) glDeleteTextures(1, &view_);
            glCreateTextures(GL_TEXTURE_BUFFER, 1, &view_);
            glTextureBuffer(view_, GL_RGBA32UI, b.id);
            of_ = b;
        }
        return view_;
    }

private:
    GLuint view_ = 0;
    Buffer of_;
};

}  // namespace pathlet::oit
