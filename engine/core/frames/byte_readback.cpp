#include "frames/byte_readback.hpp"

#include "image_io.hpp"
#include "pixel_store.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

namespace pathlet {

namespace {

bool is_unorm8(GLenum f) { return f == GL_R8 || f == GL_RG8 || f == GL_RGBA8 || f == GL_SRGB8_ALPHA8; }

// glGetTextureImage as bytes with plain pack state (read_texture does the same for floats).
std::vector<uint8_t> read_bytes(GLuint tex, int w) {
    const PlainPixelStore plain(PlainPixelStore::pack);
    std::vector<uint8_t> out(size_t(w) * 4);
    glGetTextureImage(tex, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(out.size()), out.data());
    return out;
}

}  // namespace

std::shared_ptr<const ByteTable> measure_byte_table(GLenum internal_format) {
    if (!is_unorm8(internal_format)) return nullptr;
    std::vector<uint8_t> ramp(256 * 4);
    for (size_t k = 0; k < 256; ++k)
        for (size_t c = 0; c < 4; ++c) ramp[k * 4 + c] = uint8_t(k);
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, internal_format, 256, 1);
    {
        const PlainPixelStore plain(PlainPixelStore::unpack);
        glTextureSubImage2D(tex, 0, 0, 0, 256, 1, GL_RGBA, GL_UNSIGNED_BYTE, ramp.data());
    }
    std::shared_ptr<ByteTable> table;
    try {
        const std::vector<uint8_t> bytes = read_bytes(tex, 256);
        const Image floats = read_texture(tex, 256, 1, 0, 4);
        // Every (byte, float) pair seen per channel; a byte never seen maps to NaN (it cannot
        // occur in this format: a missing channel reads as a constant).
        auto t = std::make_shared<ByteTable>();
        for (auto& ch : *t) ch.fill(std::nanf(""));
        bool consistent = true;
        for (size_t i = 0; i < bytes.size(); ++i) {
            float& slot = (*t)[i % 4][bytes[i]];
            const float v = floats.pixels[i];
            if (std::isnan(slot)) slot = v;
            else if (slot != v) consistent = false;
        }
        if (consistent) table = t;
    } catch (const std::exception&) {
    }
    glDeleteTextures(1, &tex);
    return table;
}

}  // namespace pathlet
