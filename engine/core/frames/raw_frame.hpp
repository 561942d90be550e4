// What a read-back delivers (rows bottom-up, as GL packs them, each row padded to 4 bytes) and
// the CPU work that turns it into the Image that read_texture (+ box_downsample for
// supersampling) gives: widening half floats and missing channels, flipping rows, spreading
// depth, looking 8-bit values up, dividing the GPU filter's sums. Runs on a writer thread, so
// none of it is on the render thread. The result is bit for bit the synchronous path's
// (tests/output/test_async_output.cpp, test_native_readback.cpp).
#pragma once

#include "image_io.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace pathlet {

// Per channel, the float glGetTextureImage gives for each byte value of an 8-bit format (the
// driver's own conversion, measured once: byte_table()).
using ByteTable = std::array<std::array<float, 256>, 4>;

// A read-back's bytes where they lie (a mapped pixel-pack buffer, or memory of its own), kept
// there for as long as the object lives: `keep` is what holds them (the ring's buffer is reused
// only once the last copy of it is gone, on whichever thread).
struct PackedPixels {
    const uint8_t* data = nullptr;
    size_t size = 0;
    std::shared_ptr<const void> keep;

    static PackedPixels own(std::vector<uint8_t> bytes);  // memory of its own
};

struct RawFrame {
    enum class Layout {
        Floats,  // `channels` halfs or floats a pixel (the target's own format, or GL_RGBA/GL_FLOAT)
        Depth,   // one float per pixel (the GPU's R32F copy or GL_DEPTH_COMPONENT): spread to grey, alpha 1
        Bytes,   // RGBA bytes (GL_RGBA, GL_UNSIGNED_BYTE), mapped through `table`
        Sums,    // the GPU box filter's block sums (GpuBoxFilter, RGBA floats): divided here
    };
    Layout layout = Layout::Floats;
    int width = 0, height = 0;  // of the data read
    int channels = 4;           // Floats: 1, 2 or 4 (missing ones read as GL reads them: 0, 0, 1 for alpha)
    bool half = false;          // Floats: 16-bit floats
    // Floats/Depth: box_downsample by this afterwards (the CPU filter); Sums: the block size.
    int factor = 1;
    std::shared_ptr<const ByteTable> table;  // Bytes
    PackedPixels data;                       // bottom-up rows, each padded to 4 bytes

    int bytes_per_pixel() const;
    // Bytes of a packed row (GL_PACK_ALIGNMENT 4).
    size_t row_bytes() const { return (size_t(width) * size_t(bytes_per_pixel()) + 3) / 4 * 4; }
};

// IEEE half to float, exactly (denormals, infinities; a NaN keeps its payload bits).
float half_to_float(uint16_t h);

// The Image the synchronous path gives (RGBA floats, top row first, is_float). Releases the
// packed bytes before the CPU filter runs.
Image to_image(RawFrame&& raw);

// Box filter's last step for block sums (rgb: colour weighted by alpha, or the plain colour
// where the block's alpha sum is <= 0; a: the alpha sum), exactly as box_downsample divides.
// `sums` is top row first, RGBA.
void divide_sums(std::vector<float>& sums, int factor);

}  // namespace pathlet
