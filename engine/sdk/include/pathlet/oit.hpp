// Order-independent transparency: the C++ side of the per-pixel linked lists' layout in
// shaders/oit_list.glsl (clear_list, fill_list, resolve_list, resolve_exact and any OIT pass of
// yours), and the moment forms of moment-based OIT (mboit_moments, mboit_accum).
#pragma once

#include <pathlet/gl.hpp>
#include <pathlet/pass.hpp>

#include <array>
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
// Empties every list: heads to kEnd, the node counter to 0. The last frame's fill wrote both
// with atomics: their writes land before the clears only behind the update barriers.
inline void clear_lists(GLuint heads_texture, GLuint counter_buffer) {
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glClearTexImage(heads_texture, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &kEnd);
    const GLuint zero = 0;
    glClearNamedBufferData(counter_buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

// ---- moment-based OIT (Münstermann et al. 2018) -------------------------------------------
// The moments a pixel keeps, said once for the pass that sums them (mboit_moments) and the pass
// that reconstructs from them (mboit_accum): both declare the parameter `moment_form` through
// declare_moment_form, compile their shaders with the form's defines, and wire `moments_high`
// by needs_high. The graph compiler checks that the two passes of a graph have the same form
// (the pin option same_as_writer on mboit_accum's inputs).
struct MomentForm {
    const char* name;   // the parameter's choice
    int order;          // n: 2n power moments, or n trigonometric ones (MBOIT_ORDER)
    bool trig;          // trigonometric (MBOIT_TRIG)
    float default_bias; // moment_bias < 0 takes this (mboit_accum's README says why)
    // More than 4 floats of moments: the 5th..8th (or the 3rd and 4th complex) in moments_high.
    bool needs_high() const { return order > 2; }
    std::vector<std::string> defines() const {
        std::vector<std::string> d = {"MBOIT_ORDER " + std::to_string(order)};
        if (trig) d.push_back("MBOIT_TRIG");
        return d;
    }
};
// Power moments: the paper's bias for 4 float32 moments, and the same for 6 and 8 (the
// reconstruction sums positive Christoffel weights; the paper's larger values guard its
// expectation through monomials). Trigonometric: the paper's float32 values.
inline constexpr std::array<MomentForm, 6> kMomentForms = {{{"power4", 2, false, 5e-7f},
                                                            {"power6", 3, false, 5e-7f},
                                                            {"power8", 4, false, 5e-7f},
                                                            {"trig2", 2, true, 4e-7f},
                                                            {"trig3", 3, true, 8e-7f},
                                                            {"trig4", 4, true, 1.5e-6f}}};
inline PassTypeBuilder& declare_moment_form(PassTypeBuilder& b) {
    std::vector<std::string> names;
    for (const MomentForm& f : kMomentForms) names.push_back(f.name);
    return b.param_enum("moment_form", names.front(), names,
                        "the moments of the warped depth each pixel keeps (float32): power4 (20 bytes a pixel with "
                        "b0), power6, power8 (36, the moments past the 4th in moments_high); trig2 (20), trig3, trig4 "
                        "(36): 2..4 trigonometric moments of the depth as an angle; mboit_moments and mboit_accum "
                        "must have the same (the graph compiler checks; a graph variable feeds both)");
}
// The form a pass's parameters chose.
inline const MomentForm& moment_form(const Params& p) { return kMomentForms.at(size_t(p.index("moment_form"))); }

}  // namespace pathlet::oit
