// Golden-image support: pass on identical, fail (with actual/expected/diff images) on change,
// missing goldens fail unless PATHLET_UPDATE_GOLDENS=1, plus the probe helpers.
#include "golden.hpp"
#include "scratch_dir.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

namespace pathlet {
namespace {

Image gradient(int w, int h) {
    Image img;
    img.width = w;
    img.height = h;
    img.channels = 4;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img.pixels.insert(img.pixels.end(), {float(x) / float(w), float(y) / float(h), 0.25f, 1.0f});
    return img;
}

// Points failure images and the update switch at this test, and puts them back after.
class GoldenTest : public ::testing::Test {
protected:
    void SetUp() override {
        ::setenv("PATHLET_GOLDEN_FAILURE_DIR", (dir / "failures").c_str(), 1);
        ::unsetenv("PATHLET_UPDATE_GOLDENS");
    }
    void TearDown() override {
        ::unsetenv("PATHLET_GOLDEN_FAILURE_DIR");
        ::unsetenv("PATHLET_UPDATE_GOLDENS");
    }
    ScratchDir dir;
};

TEST_F(GoldenTest, IdenticalAndSubLsbNoisePass) {
    Image img = gradient(64, 32);
    write_image(dir / "grad.png", img);
    EXPECT_TRUE(matches_golden(img, dir / "grad.png"));
    for (float& v : img.pixels) v += 0.001f;  // below half an 8-bit step: same PNG
    EXPECT_TRUE(matches_golden(img, dir / "grad.png"));
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "failures"));
}

TEST_F(GoldenTest, ChangedPixelFailsAndWritesDiffImages) {
    Image img = gradient(64, 32);
    write_image(dir / "grad.png", img);
    img.at(10, 5, 2) = 0.75f;  // one pixel, blue 0.25 -> 0.75
    ::testing::AssertionResult r = matches_golden(img, dir / "grad.png", 2.0 / 255, 0.0);
    ASSERT_FALSE(r);
    const std::string msg = r.message();
    EXPECT_NE(msg.find("1 of 2048 pixels"), std::string::npos) << msg;
    EXPECT_NE(msg.find("max error 0.498"), std::string::npos) << msg;  // (191 - 64) / 255
    EXPECT_NE(msg.find("(10,5)"), std::string::npos) << msg;
    const std::string base = dir / "failures/grad";
    EXPECT_NE(msg.find(base + ".actual.png"), std::string::npos) << msg;
    Image diff = read_image(base + ".diff.png");
    EXPECT_FLOAT_EQ(diff.at(10, 5, 2), 1.0f);  // 0.5 x 8, clamped
    EXPECT_FLOAT_EQ(diff.at(11, 5, 2), 0.0f);
    EXPECT_FLOAT_EQ(diff.at(11, 5, 3), 1.0f);  // opaque
    EXPECT_EQ(read_image(base + ".expected.png").at(10, 5, 2), 64.0f / 255.0f);
    EXPECT_EQ(read_image(base + ".actual.png").at(10, 5, 2), 191.0f / 255.0f);

    // The default budget (0.05 % of 2048 pixels = 1 pixel) tolerates exactly this one.
    EXPECT_TRUE(matches_golden(img, dir / "grad.png"));
}

TEST_F(GoldenTest, SizeMismatchFails) {
    write_image(dir / "grad.png", gradient(64, 32));
    ::testing::AssertionResult r = matches_golden(gradient(32, 32), dir / "grad.png");
    ASSERT_FALSE(r);
    EXPECT_NE(std::string(r.message()).find("64x32x4"), std::string::npos) << r.message();
}

TEST_F(GoldenTest, NanFails) {
    Image img = gradient(8, 8);
    write_image(dir / "grad.png", img);
    img.at(3, 3, 0) = std::nanf("");
    EXPECT_TRUE(has_nan(img));
    EXPECT_FALSE(matches_golden(img, dir / "grad.png"));
}

TEST_F(GoldenTest, MissingGoldenFailsUnlessUpdating) {
    const std::string golden = dir / "goldens/new.png";
    ::testing::AssertionResult r = matches_golden(gradient(16, 16), golden);
    ASSERT_FALSE(r);
    EXPECT_NE(std::string(r.message()).find("PATHLET_UPDATE_GOLDENS=1"), std::string::npos) << r.message();
    EXPECT_FALSE(std::filesystem::exists(golden));

    ::setenv("PATHLET_UPDATE_GOLDENS", "1", 1);
    EXPECT_TRUE(matches_golden(gradient(16, 16), golden));
    ASSERT_TRUE(std::filesystem::exists(golden));
    ::unsetenv("PATHLET_UPDATE_GOLDENS");
    EXPECT_TRUE(matches_golden(gradient(16, 16), golden));
    // No temp files left beside the new golden.
    size_t files = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path() / "goldens")) ++files;
    EXPECT_EQ(files, 1u);
}

TEST(ImageProbes, LuminanceAndColourCounts) {
    Image img;
    img.width = 4;
    img.height = 2;
    img.channels = 4;
    img.pixels.assign(4 * 2 * 4, 0.0f);
    for (int x = 0; x < 4; ++x) img.at(x, 0, 1) = 1.0f, img.at(x, 0, 3) = 1.0f;  // top row green
    EXPECT_NEAR(mean_luminance(img, {0, 0, 4, 1}), 0.7152, 1e-9);
    EXPECT_NEAR(mean_luminance(img, {0, 1, 4, 1}), 0.0, 1e-9);
    EXPECT_NEAR(mean_luminance(img), 0.7152 / 2, 1e-9);
    EXPECT_THROW(mean_luminance(img, {2, 0, 4, 1}), std::out_of_range);
    EXPECT_EQ(count_pixels_equal(img, {0, 1, 0, 1}), 4u);
    EXPECT_EQ(count_pixels_equal(img, {0, 0.99f, 0, 1}, 0.02f), 4u);
    EXPECT_EQ(count_pixels_equal(img, {0, 0, 0, 0}), 4u);
    EXPECT_FALSE(has_nan(img));
}

}  // namespace
}  // namespace pathlet
