#include "frames/native_readback.hpp"

#include "formats.hpp"
#include "frames/raw_frame.hpp"
#include "image_io.hpp"
#include "pixel_store.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace pathlet {

bool native_read(GLenum internal_format, NativeRead& out) {
    const FormatInfo* fi = find_format(internal_format);
    if (!fi || !fi->is_float || fi->depth || (fi->pixel_type != GL_HALF_FLOAT && fi->pixel_type != GL_FLOAT) ||
        fi->channels == 3)
        return false;
    out.format = fi->pixel_format;
    out.type = fi->pixel_type;
    out.channels = fi->channels;
    out.half = fi->pixel_type == GL_HALF_FLOAT;
    return true;
}

bool widening_exact(GLenum internal_format) {
    NativeRead n;
    if (!native_read(internal_format, n)) return false;
    if (!n.half) return true;
    // Every half pattern in every channel (rotated per channel), read both ways.
    const int w = 256, h = 256;
    const size_t px = size_t(w) * size_t(h), ch = size_t(n.channels);
    std::vector<uint16_t> pattern(px * ch);
    for (size_t i = 0; i < px; ++i)
        for (size_t c = 0; c < ch; ++c) pattern[i * ch + c] = uint16_t(i + c * 4099);
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, internal_format, w, h);
    bool same = false;
    try {
        std::vector<uint8_t> bytes(pattern.size() * 2);
        {
            const PlainPixelStore unpack(PlainPixelStore::unpack);
            glTextureSubImage2D(tex, 0, 0, 0, w, h, n.format, n.type, pattern.data());
        }
        {
            const PlainPixelStore pack(PlainPixelStore::pack);
            glGetTextureImage(tex, 0, n.format, n.type, GLsizei(bytes.size()), bytes.data());
        }
        RawFrame raw;
        raw.layout = RawFrame::Layout::Floats;
        raw.width = w;
        raw.height = h;
        raw.channels = n.channels;
        raw.half = true;
        raw.data = PackedPixels::own(std::move(bytes));
        const Image mine = to_image(std::move(raw));
        const Image theirs = read_texture(tex, w, h, 0, 4);
        same = mine.pixels.size() == theirs.pixels.size();
        for (size_t i = 0; same && i < mine.pixels.size(); ++i) {
            const float a = mine.pixels[i], b = theirs.pixels[i];
            same = std::memcmp(&a, &b, 4) == 0 || (std::isnan(a) && std::isnan(b));
        }
    } catch (const std::exception&) {
        same = false;
    }
    glDeleteTextures(1, &tex);
    return same;
}

}  // namespace pathlet
