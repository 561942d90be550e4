// Images on the CPU side: reading/writing files through OpenImageIO, or PNG through stb in a
// build without it (image_io_stb.cpp; never half-written: temp name + rename), reading GL
// textures back, and capture path patterns.
#pragma once

#include <pathlet/gl.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace pathlet {

// How every PNG Pathlet writes is compressed: frames are encoded while the next ones render, on
// the same cores. zlib level 1 and the UP filter on every row (libpng's adaptive choice of a
// filter per row was half the encoding time) make files ~20 % larger than the libraries'
// defaults at under half the CPU (llvmpipe, 2 cores, 720p: docs/performance.md).
constexpr int kPngCompressionLevel = 1;
constexpr int kPngFilterUp = 2;  // the PNG filter type "Up" (libpng's mask for it: 0x10 << 2)

struct Image {
    int width = 0, height = 0, channels = 4;
    bool is_float = false;      // source precision: float/half data, not 8-bit
    std::vector<float> pixels;  // interleaved channels, top row first

    float& at(int x, int y, int c) { return pixels[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c)]; }
    float at(int x, int y, int c) const { return pixels[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c)]; }
};

// The one float -> 8-bit rule (clamp to [0,1], round to nearest, halves up), shared by PNG
// output, video frames and golden comparisons. Inline, so a frame's loop over it vectorises
// (it is on every written frame's path); x + 0.5 in double is exact, so the truncation is
// std::lround(x) exactly.
inline uint8_t to_unorm8(float v) {
    if (!(v > 0.0f)) return 0;  // also NaN
    if (v >= 1.0f) return 255;
    const float x = v * 255.0f;
    return uint8_t(double(x) + 0.5);
}
// Interleaved RGBA8, top row first; grey is replicated, missing alpha is opaque.
std::vector<uint8_t> to_rgba8(const Image& img);

// Pixel values go to and come from files unchanged (no alpha premultiplication either way).
// Format from the extension (PNG when there is none). EXR (and float TIFF) keep 32-bit
// float; 8-bit formats get clamped and rounded values. Atomic: a temp name that keeps the
// extension, then rename. Throws std::runtime_error naming the file.
void write_image(const std::string& path, const Image& img);
Image read_image(const std::string& path);  // throws std::runtime_error naming the file
// Throws std::runtime_error naming `path` unless the size, channels and values agree (before a write).
void check_image_shape(const Image& img, const std::string& path);

// Reads mip level `mip` of a 2D texture as float with glGetTextureImage; w, h are that
// level's size (checked). GL's bottom-up rows are flipped to top row first.
Image read_texture(GLuint tex, int w, int h, int mip = 0, int channels = 4);
// Box filter over factor x factor blocks (supersampling's resolve). With 4 channels the colour
// is averaged weighted by alpha, so transparent pixels add no colour to an edge.
Image box_downsample(const Image& img, int factor);

// "out/{graph}/{frame:05}.png" -> "out/lineao/00012.png". {name} comes from vars, {frame}
// and {frame:0N} from `frame`, "{{" and "}}" are literal braces. Throws
// std::invalid_argument on an unknown name or a malformed pattern.
std::string expand_pattern(const std::string& pattern, const std::map<std::string, std::string>& vars,
                           uint64_t frame);
// Creates the directory that will hold `path` (nothing when it has none).
void ensure_parent_dir(const std::string& path);

}  // namespace pathlet
