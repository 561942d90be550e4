// Read-back in the target's own format (frames/native_readback.hpp, gpu_depth_copy.hpp): every
// float and depth format goes into the pack buffer at its own size (r16f: 2 bytes a pixel, depth
// as the GPU's R32F copy) and comes out of a writer as the floats read_texture gives, bit for
// bit: halfs with denormals and infinities, missing channels, odd widths (padded rows).
#include "formats.hpp"
#include "frame_capture.hpp"
#include "frames/async_output.hpp"
#include "frames/gpu_depth_copy.hpp"
#include "frames/native_readback.hpp"
#include "image_io.hpp"
#include "pixel_store.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

namespace pathlet {
namespace {

// A w x h texture of `format` with values that test the widening: for half formats every kind
// of half (normal, denormal, zero, infinity, negative), for others random floats.
Texture pattern_texture(GLenum format, int w, int h) {
    const FormatInfo* fi = find_format(format);
    Texture t;
    t.width = w, t.height = h, t.internal_format = format;
    glCreateTextures(GL_TEXTURE_2D, 1, &t.id);
    glTextureStorage2D(t.id, 1, format, w, h);
    std::mt19937 rng(format);
    const PlainPixelStore unpack(PlainPixelStore::unpack);
    if (fi->pixel_type == GL_HALF_FLOAT) {
        // Rows padded to the unpack alignment (4): GL reads every row at that stride.
        const size_t row = size_t(w) * size_t(fi->channels) * 2;
        std::vector<uint16_t> v((row + 3) / 4 * 4 / 2 * size_t(h));
        for (size_t i = 0; i < v.size(); ++i) {
            uint16_t h16 = uint16_t(rng());
            if ((h16 & 0x7c00u) == 0x7c00u) h16 &= 0xfc00u;  // infinities stay, NaNs become infinities
            v[i] = i % 7 == 0 ? uint16_t(i % 0x400) : h16;    // every seventh a denormal (or zero)
        }
        glTextureSubImage2D(t.id, 0, 0, 0, w, h, fi->pixel_format, GL_HALF_FLOAT, v.data());
    } else if (fi->depth) {
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::vector<float> v(size_t(w) * size_t(h));
        for (float& x : v) x = unit(rng);
        glTextureSubImage2D(t.id, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, v.data());
    } else {
        std::uniform_real_distribution<float> any(-4.0f, 4.0f);
        std::vector<float> v(size_t(w) * size_t(h) * 4);
        for (float& x : v) x = any(rng);
        glTextureSubImage2D(t.id, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, v.data());
    }
    return t;
}

size_t packed_row(int w, int bytes_per_pixel) { return (size_t(w) * size_t(bytes_per_pixel) + 3) / 4 * 4; }

struct Case {
    const char* name;
    int bytes_per_pixel;  // in the pack buffer
};

TEST(NativeReadback, EveryFormatIsReadAtItsOwnSizeAndWidenedToTheDriversFloats) {
    test_runtime();  // the GL context
    const Case cases[] = {{"r16f", 2},  {"rg16f", 4},   {"rgba16f", 8}, {"r32f", 4},     {"rg32f", 8},
                          {"rgba32f", 16}, {"depth16", 4}, {"depth24", 4}, {"depth32f", 4}, {"rgba8", 4}};
    const int w = 13, h = 7;  // odd: r16f rows are padded to 4 bytes
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const Texture tex = pattern_texture(find_format(c.name)->internal_format, w, h);
        std::vector<Image> seen;
        AsyncOutput::Options o;
        o.threads = 1;
        o.on_image = [&](const Image& img) { seen.push_back(img); };
        {
            AsyncOutput out(o);
            out.capture({{c.name, tex, "", true}});
            out.finish();
            EXPECT_EQ(out.bytes_read_back(), packed_row(w, c.bytes_per_pixel) * size_t(h)) << "not read in its own format";
        }
        const Image sync = read_texture(tex.id, w, h, 0, 4);
        ASSERT_EQ(seen.size(), 1u);
        ASSERT_EQ(seen[0].pixels.size(), sync.pixels.size());
        size_t differ = 0, first = 0;
        for (size_t i = 0; i < sync.pixels.size(); ++i)
            if (std::memcmp(&seen[0].pixels[i], &sync.pixels[i], 4) != 0 && differ++ == 0) first = i;
        EXPECT_EQ(differ, 0u) << "first at float " << first << ": " << seen[0].pixels[first] << ", read_texture "
                              << sync.pixels[first];
        glDeleteTextures(1, &tex.id);
    }
}

TEST(NativeReadback, TheWideningAndTheDepthCopyAreExactOnThisDriver) {
    // Not a fallback in disguise: on llvmpipe halfs are widened on the writers and depth is
    // copied to R32F on the GPU (else the test above would pass on the RGBA32F path alone).
    test_runtime();
    for (GLenum f : {GL_R16F, GL_RG16F, GL_RGBA16F, GL_R32F, GL_RGBA32F}) EXPECT_TRUE(widening_exact(f)) << std::hex << f;
    // (llvmpipe's texelFetch of depth24 is a step off its pixel path's value in one of two
    // ways to a float, so depth24 is read as it is there: not asserted either way.)
    GpuDepthCopy depth;
    for (GLenum f : {GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT32F}) EXPECT_TRUE(depth.exact(f)) << std::hex << f;
    NativeRead n;
    for (GLenum f : {GL_RGBA8, GL_R11F_G11F_B10F, GL_R32UI, GL_DEPTH_COMPONENT24})
        EXPECT_FALSE(native_read(f, n)) << "read as RGBA floats (or bytes, or depth): " << std::hex << f;
}

TEST(NativeReadback, AnIntegerOutputIsAClearErrorBeforeAnythingIsRead) {
    test_runtime();
    Texture t;
    t.width = 4, t.height = 4, t.internal_format = GL_R32UI;
    glCreateTextures(GL_TEXTURE_2D, 1, &t.id);
    glTextureStorage2D(t.id, 1, GL_R32UI, 4, 4);
    AsyncOutput out(AsyncOutput::Options{});
    std::string error;
    try {
        out.capture({{"output 'ids'", t, "", false}});
    } catch (const std::runtime_error& e) {
        error = e.what();
    }
    EXPECT_NE(error.find("output 'ids': cannot read the texture back: r32ui"), std::string::npos) << error;
    EXPECT_EQ(out.bytes_read_back(), 0u);
    glDeleteTextures(1, &t.id);
}

}  // namespace
}  // namespace pathlet
