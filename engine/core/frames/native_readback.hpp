// Float outputs read back in their own format: an r16f target is 2 bytes a pixel into the pack
// buffer, not the 16 of RGBA32F, and the writer widens it (raw_frame.hpp) to the floats
// glGetTextureImage(GL_RGBA, GL_FLOAT) gives. For 32-bit floats that is the same value by the
// spec; for half floats it is a conversion of our own, so it is measured once per format against
// the driver's on every 16-bit pattern (NaNs only as NaNs: their payload bits are the driver's
// choice). GL thread only.
#pragma once

#include <pathlet/gl.hpp>

namespace pathlet {

struct NativeRead {
    GLenum format = GL_RGBA, type = GL_FLOAT;  // glGetTextureImage's
    int channels = 4;
    bool half = false;
};

// r16f, rg16f, rgba16f, r32f, rg32f, rgba32f: how each is read; false for every other format.
bool native_read(GLenum internal_format, NativeRead& out);

// For a format native_read() takes: whether the writer's widening equals the driver's floats on
// this driver (always true for 32-bit floats; measured for half floats).
bool widening_exact(GLenum internal_format);

}  // namespace pathlet
