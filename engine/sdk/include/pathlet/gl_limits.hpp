// The GL limits the engine works within: binding points and per-stage resource counts, queried
// from the context, or the GL 4.5 core minimum for every one of them when the environment says
// PATHLET_GL_LIMITS=minimum (a minimal driver emulated on any machine: NVIDIA has exactly the
// minimum 8 image units, llvmpipe 192). Units and binding points are numbered by the engine
// within these (executor), and every linked program is checked against them per stage
// (check_program_limits), so a shader that would fail on a minimal driver fails everywhere,
// naming the limit, what it asked for and what the context allows.
#pragma once

#include <pathlet/gl.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace pathlet {

struct GlLimit {
    const char* name;  // "GL_MAX_IMAGE_UNITS"
    GLenum pname;
    int minimum;       // the GL 4.5 core profile's required minimum (spec, tables 23.57-23.67)
    // A count of units, binding points or resources, which minimum mode emulates, as it does
    // the storage block size (128 MiB holds every shipped graph at 1080p). Other sizes (the
    // largest texture, texture buffer) are printed but always the context's: a driver at those
    // minimums could not hold the study's data at all.
    bool emulated = true;
};

// Every limit the engine queries and enforces, in the order `pathlet info --gl` prints them.
const std::vector<GlLimit>& gl_limit_table();

class GlLimits {
public:
    // The value the engine uses: the context's, or the limit's minimum in minimum mode.
    int get(GLenum pname) const;
    // The context's own value, whatever the mode.
    int context_value(GLenum pname) const;
    bool minimum_mode() const { return minimum_; }
    // " (GL_MAX_IMAGE_UNITS)" or " (GL_MAX_IMAGE_UNITS: the GL 4.5 minimum, PATHLET_GL_LIMITS=minimum)".
    std::string source(GLenum pname) const;

private:
    friend const GlLimits& gl_limits();
    bool minimum_ = false;
    std::vector<int> context_;  // by gl_limit_table() index
};

// GLSL opaque types by GL type enum: a sampler (takes a texture unit) or an image (an image unit).
bool is_sampler_type(GLenum type);
bool is_image_type(GLenum type);

// The limits for the current context (queried on first use, again when PATHLET_GL_LIMITS changes).
// PATHLET_GL_LIMITS: unset or "context" = the context's; "minimum" = the GL 4.5 minimum; anything
// else is an error naming the variable.
const GlLimits& gl_limits();

// A storage block of `bytes` that `what` needs `at` a size ("at 1920x1080" for a buffer of the
// picture's pixels, "for 3,169 lines" for the data's): throws std::runtime_error naming both and
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE when the block is larger (access beyond it is undefined and
// nothing would report it). `hint` ends the message (what would fit). Call it in setup, where
// the size is known, as every pass with a storage block sized by the picture or the data does.
void check_storage_block(size_t bytes, const std::string& what, const std::string& at, const std::string& hint = "");
// "at 1920x1080"
std::string at_picture_size(int width, int height);

// Checks a linked program's active resources, per stage and combined, against gl_limits():
// samplers, images, storage and uniform blocks, their binding points, fragment outputs and the
// combined output resources, compute work-group size. Throws ShaderError naming `what` (the
// program's files), the stage, the limit, what it asks for and what the context allows.
void check_program_limits(GLuint program, const std::string& what);

}  // namespace pathlet
