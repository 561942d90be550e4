// What a read-back delivers (rows bottom-up, as GL packs them) and the CPU work that turns it
// into the Image that read_texture (+ box_downsample for supersampling) gives: flipping rows,
// spreading depth, looking 8-bit values up, dividing the GPU filter's sums. Runs on a writer
// thread, so none of it is on the render thread. The result is bit for bit the synchronous
// path's (tests/engine/test_async_output.cpp).
#pragma once

#include "image_io.hpp"

#include <array>
#include <memory>
#include <vector>

namespace pathlet {

// Per channel, the float glGetTextureImage gives for each byte value of an 8-bit format (the
// driver's own conversion, measured once: byte_table()).
using ByteTable = std::array<std::array<float, 256>, 4>;

struct RawFrame {
    enum class Layout {
        Floats,  // RGBA floats (GL_RGBA, GL_FLOAT): read_texture's values
        Depth,   // one float per pixel (GL_DEPTH_COMPONENT): spread to grey, alpha 1
        Bytes,   // RGBA bytes (GL_RGBA, GL_UNSIGNED_BYTE), mapped through `table`
        Sums,    // the GPU box filter's block sums (GpuBoxFilter): divided here
    };
    Layout layout = Layout::Floats;
    int width = 0, height = 0;  // of the data read
    // Floats/Depth: box_downsample by this afterwards (the CPU filter); Sums: the block size.
    int factor = 1;
    std::shared_ptr<const ByteTable> table;  // Bytes
    std::vector<float> data;                 // bottom-up rows; Bytes use the storage as bytes

    static int bytes_per_pixel(Layout l) { return l == Layout::Depth ? 4 : l == Layout::Bytes ? 4 : 16; }
};

// The Image the synchronous path gives (RGBA floats, top row first, is_float).
Image to_image(RawFrame&& raw);

// Box filter's last step for block sums (rgb: colour weighted by alpha, or the plain colour
// where the block's alpha sum is <= 0; a: the alpha sum), exactly as box_downsample divides.
// `sums` is top row first, RGBA.
void divide_sums(std::vector<float>& sums, int factor);

}  // namespace pathlet
