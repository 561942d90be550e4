// Supersampling's resolve on the GPU, so a frame is read back at its final size: a small
// fragment pass in the engine (not a graph pass) that gives, per output pixel, the sums that
// box_downsample forms, added in its order with `precise` operations (no fused multiply-add):
// colour weighted by alpha (or the plain colour where the block's alpha sum is <= 0) and the
// alpha sum. The division stays on the CPU (divide_sums), because GLSL's is not correctly
// rounded. Whether a driver's texel fetch gives the values glGetTextureImage gives (sRGB
// decoding, 8-bit conversion) is measured once per format and factor on a test pattern:
// exact() is false on any difference in any bit, and the caller filters on the CPU instead.
// GL thread only; the context must be current, the destructor included.
#pragma once

#include <pathlet/gl.hpp>
#include "output_program.hpp"

#include <cstddef>
#include <map>
#include <utility>
#include <vector>

namespace pathlet {

class GpuBoxFilter {
public:
    GpuBoxFilter() = default;
    ~GpuBoxFilter();
    GpuBoxFilter(const GpuBoxFilter&) = delete;
    GpuBoxFilter& operator=(const GpuBoxFilter&) = delete;

    // True when sums() + divide_sums() equal box_downsample(read_texture(...)) bit for bit for
    // textures of this format at this factor on this driver (measured on first use).
    bool exact(GLenum internal_format, int factor);

    // Renders the block sums of level 0 of `src` ((w * factor) x (h * factor)) into an RGBA32F
    // texture of w x h that the filter owns, one per `slot` (reused frame after frame), and
    // returns it. Leaves program, framebuffer, vertex array and texture unit 0 unbound.
    GLuint sums(GLuint src, int w, int h, int factor, size_t slot);

private:
    void ensure_program();
    bool measure(GLenum internal_format, int factor);

    GLuint program_ = 0, vao_ = 0;
    GLint factor_loc_ = -1;
    OutputTargets targets_{GL_RGBA32F};
    std::map<std::pair<GLenum, int>, bool> exact_;
};

}  // namespace pathlet
