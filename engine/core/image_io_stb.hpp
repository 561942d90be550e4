// PNG files through stb (Debian libstb-dev, header only): the image backend of a build without
// OpenImageIO (PATHLET_WITH_OPENIMAGEIO=OFF, the lean bundle), where write_image/read_image
// are these. Compiled into its test in the full build too (tests/profiler/test_image_io_stb.cpp).
#pragma once

#include "image_io.hpp"

namespace pathlet::stb {

// write_image's contract (image_io.hpp) for .png (or no extension); any other name is refused,
// naming the file and saying this build has no EXR (float formats) or writes PNG only.
void write_png(const std::string& path, const Image& img);
// read_image's contract for .png files (8 or 16 bits, 1 to 4 channels).
Image read_png(const std::string& path);

}  // namespace pathlet::stb
