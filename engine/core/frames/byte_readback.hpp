// 8-bit outputs read back as bytes: a quarter of the float read-back's size. The floats an
// Image holds are then the driver's own conversion of each byte (what glGetTextureImage with
// GL_FLOAT gives, sRGB formats included), measured once per format by reading a texture of
// every byte value both ways, so the Image is the synchronous path's bit for bit.
// GL thread only.
#pragma once

#include "frames/raw_frame.hpp"

#include <pathlet/gl.hpp>

#include <memory>

namespace pathlet {

// The byte -> float table of an 8-bit unsigned normalised colour format (r8, rg8, rgba8,
// rgba8_srgb), or nullptr for other formats and where one byte would give two floats.
std::shared_ptr<const ByteTable> measure_byte_table(GLenum internal_format);

}  // namespace pathlet
