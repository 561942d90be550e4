// Depth outputs as R32F on the GPU, so a depth capture is read back as plain floats: a depth
// texture through the driver's pixel path (GL_DEPTH_COMPONENT into a pack buffer) is a CPU
// conversion on many drivers, which would stall the frame that captures it. A small fragment
// pass copies texelFetch's depth into an R32F target, or takes a normalised depth back to its
// integer and divides it as a CPU pixel path does (whichever is exact). Whether that gives the floats
// glGetTextureImage(GL_DEPTH_COMPONENT, GL_FLOAT) gives (the unorm-to-float conversion of depth16
// and depth24) is measured once per format on a test pattern, as GpuBoxFilter measures itself:
// exact() is false on any difference in any bit, and the caller reads the depth as it is.
// GL thread only; the context must be current, the destructor included.
#pragma once

#include <pathlet/gl.hpp>
#include "output_program.hpp"

#include <cstddef>
#include <map>
#include <vector>

namespace pathlet {

class GpuDepthCopy {
public:
    GpuDepthCopy() = default;
    ~GpuDepthCopy();
    GpuDepthCopy(const GpuDepthCopy&) = delete;
    GpuDepthCopy& operator=(const GpuDepthCopy&) = delete;

    // True when to_float() then a GL_RED/GL_FLOAT read gives what reading the depth texture as
    // GL_DEPTH_COMPONENT/GL_FLOAT gives, bit for bit, for this format on this driver. (llvmpipe:
    // depth16 and depth32f; its texelFetch of depth24 is a step off the pixel path's value.)
    bool exact(GLenum depth_format);

    // Copies level 0 of the depth texture `src` (`depth_format`, w x h) into an R32F texture the
    // copy owns, one per `slot` (reused frame after frame), and returns it. Never waits.
    GLuint to_float(GLuint src, GLenum depth_format, int w, int h, size_t slot);

private:
    bool measure(GLenum depth_format);

    GLuint program_ = 0, vao_ = 0, sampler_ = 0;
    GLint steps_loc_ = -1;
    OutputTargets targets_{GL_R32F};
    std::map<GLenum, int> exact_;  // the exact mode (kFragment's): 0, 1, or -1 for none
};

}  // namespace pathlet
