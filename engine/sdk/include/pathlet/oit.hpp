// Order-independent transparency through per-pixel linked lists: the C++ side of the layout in
// shaders/oit_list.glsl, for clear_list, fill_list, resolve_list and any OIT pass of yours.
#pragma once

#include <pathlet/gl.hpp>

#include <cstddef>

namespace pathlet::oit {

constexpr GLuint kEnd = 0xFFFFFFFFu;      // empty list / last node (OIT_END)
constexpr size_t kNodeBytes = 16;         // uvec4: colour, depth, next, line id
constexpr GLuint kCounterBinding = 8;     // OIT_COUNTER_BINDING: std430 { uint count; }

// Empties every list: heads to kEnd, the node counter to 0.
inline void clear_lists(GLuint heads_texture, GLuint counter_buffer) {
    glClearTexImage(heads_texture, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &kEnd);
    const GLuint zero = 0;
    glClearNamedBufferData(counter_buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

}  // namespace pathlet::oit
