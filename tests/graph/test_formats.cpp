#include "formats.hpp"

#include <gtest/gtest.h>

using namespace pathlet;

TEST(Formats, EveryNameRoundTripsThroughItsGlEnum) {
    const auto names = format_names();
    EXPECT_EQ(names.size(), 20u);
    for (const auto& n : names) {
        const FormatInfo* f = find_format(n);
        ASSERT_NE(f, nullptr) << n;
        EXPECT_EQ(find_format(f->internal_format), f) << n;
        EXPECT_GT(f->bytes_per_pixel, 0) << n;
    }
    EXPECT_EQ(find_format("rgba9"), nullptr);
    EXPECT_EQ(find_format(GLenum(0)), nullptr);
}

TEST(Formats, PropertiesOfSomeFormats) {
    EXPECT_EQ(find_format("rgba16f")->internal_format, GLenum(GL_RGBA16F));
    EXPECT_EQ(find_format("rgba16f")->bytes_per_pixel, 8);
    EXPECT_TRUE(find_format("rgba16f")->is_float);
    EXPECT_EQ(find_format("rgba8_srgb")->internal_format, GLenum(GL_SRGB8_ALPHA8));
    EXPECT_TRUE(find_format("depth32f")->depth);
    EXPECT_FALSE(find_format("r8")->depth);
    EXPECT_TRUE(find_format("r32ui")->is_integer);
    EXPECT_EQ(find_format("r32ui")->pixel_format, GLenum(GL_RED_INTEGER));
    EXPECT_EQ(find_format("rg8")->channels, 2);
}
