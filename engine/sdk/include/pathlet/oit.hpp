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
constexpr GLenum kNodeFormat = GL_RGBA32UI;  // the nodes as a buffer texture (PassContext::buffer_texture)

// The constants above for oit_list.glsl: add them to the defines of every program that
// includes it, so GLSL never repeats a number. (The node counter is a buffer pin: its binding
// point is the engine's, COUNTER_BINDING for a pin named "counter".)
inline std::vector<std::string> defines() { return {"OIT_END " + std::to_string(kEnd) + "u"}; }
// The list resolves' sort (shaders/oit_block_sort.glsl): fragments sorted per round in a local
// array. Declared once for every resolve that sorts so; the pass defines OIT_BLOCK from it.
inline PassTypeBuilder& declare_sort_block(PassTypeBuilder& b, const std::string& more = "") {
    return b.param_int("sort_block", 16, 1, 64,
                       "fragments sorted per round in a local array (registers): a round walks the whole list, so "
                       "fewer rounds of a larger block suit lists of many faint fragments" + more);
}
// Empties every list: heads to kEnd, the node counter to 0.
inline void clear_lists(GLuint heads_texture, GLuint counter_buffer) {
    glClearTexImage(heads_texture, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &kEnd);
    const GLuint zero = 0;
    glClearNamedBufferData(counter_buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

}  // namespace pathlet::oit
