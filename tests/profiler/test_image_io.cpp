// Image files (PNG/EXR round trips, atomic writes, errors naming the file) and capture paths.
#include "image_io.hpp"
#include "error_text.hpp"
#include "scratch_dir.hpp"
#include "unorm8_reference.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>

namespace pathlet {
namespace {

Image test_image(int w, int h, int channels, float scale = 1.0f) {
    Image img;
    img.width = w;
    img.height = h;
    img.channels = channels;
    img.is_float = true;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c) img.pixels.push_back(scale * (float(x + 3 * y) / float(w + 3 * h) + 0.1f * c));
    return img;
}

std::string what_of(const std::function<void()>& f) { return pathlet::test::error_text<std::exception>(f); }

TEST(ExpandPattern, SubstitutesNamesAndPaddedFrames) {
    std::map<std::string, std::string> vars{{"graph", "lineao"}, {"out", "renders"}};
    EXPECT_EQ(expand_pattern("out/{graph}/{frame:05}.png", vars, 12), "out/lineao/00012.png");
    EXPECT_EQ(expand_pattern("{out}/{frame}.exr", vars, 7), "renders/7.exr");
    EXPECT_EQ(expand_pattern("{frame:03}", vars, 12345), "12345");  // never truncates
    EXPECT_EQ(expand_pattern("{{literal}}_{frame:2}", vars, 3), "{literal}_03");
    EXPECT_EQ(expand_pattern("plain.png", vars, 1), "plain.png");
}

TEST(ExpandPattern, RejectsUnknownNamesAndBadSyntax) {
    std::map<std::string, std::string> vars{{"graph", "g"}};
    const std::string unknown = what_of([&] { expand_pattern("{grpah}/{frame}.png", vars, 0); });
    EXPECT_NE(unknown.find("grpah"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("graph"), std::string::npos) << "lists the known names: " << unknown;
    EXPECT_THROW(expand_pattern("{frame:abc}", vars, 0), std::invalid_argument);
    EXPECT_THROW(expand_pattern("{graph:03}", vars, 0), std::invalid_argument);
    EXPECT_THROW(expand_pattern("{frame", vars, 0), std::invalid_argument);
    EXPECT_THROW(expand_pattern("frame}", vars, 0), std::invalid_argument);
}

TEST(ImageIo, PngRoundTripClampsAndRounds) {
    ScratchDir dir;
    Image img = test_image(5, 3, 4);
    img.at(0, 0, 0) = -0.5f;  // clamped to 0
    img.at(1, 0, 0) = 1.5f;   // clamped to 1
    img.at(2, 0, 0) = 0.5f;   // 127.5 rounds to 128
    write_image(dir / "a.png", img);
    Image back = read_image(dir / "a.png");
    ASSERT_EQ(back.width, 5);
    ASSERT_EQ(back.height, 3);
    ASSERT_EQ(back.channels, 4);
    EXPECT_FALSE(back.is_float);
    EXPECT_FLOAT_EQ(back.at(0, 0, 0), 0.0f);
    EXPECT_FLOAT_EQ(back.at(1, 0, 0), 1.0f);
    EXPECT_FLOAT_EQ(back.at(2, 0, 0), 128.0f / 255.0f);
    for (size_t i = 3; i < img.pixels.size(); ++i)  // top row stays first, every value within half an LSB
        EXPECT_NEAR(back.pixels[i], std::clamp(img.pixels[i], 0.0f, 1.0f), 0.5f / 255.0f + 1e-6f) << i;
}

TEST(ImageIo, ExrRoundTripKeepsExactFloats) {
    ScratchDir dir;
    Image img = test_image(7, 4, 4, 37.0f);
    img.at(1, 2, 3) = -1234.5678f;
    img.at(6, 3, 0) = 1e-7f;
    write_image(dir / "depth.exr", img);
    Image back = read_image(dir / "depth.exr");
    EXPECT_TRUE(back.is_float);
    ASSERT_EQ(back.pixels.size(), img.pixels.size());
    for (size_t i = 0; i < img.pixels.size(); ++i) ASSERT_EQ(back.pixels[i], img.pixels[i]) << i;
}

TEST(ImageIo, SingleChannelAndNoExtensionWritesPng) {
    ScratchDir dir;
    Image grey = test_image(4, 4, 1);
    write_image(dir / "mask", grey);
    std::ifstream in(dir / "mask", std::ios::binary);
    char magic[4] = {};
    in.read(magic, 4);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

TEST(ImageIo, AtomicWriteLeavesOnlyTheTarget) {
    ScratchDir dir;
    write_image(dir / "frame.png", test_image(8, 8, 4));
    write_image(dir / "frame.png", test_image(8, 8, 4, 0.5f));  // replace in place
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"frame.png"});
}

TEST(ImageIo, FailedWriteThrowsNamingThePathAndLeavesNothing) {
    ScratchDir dir;
    const std::string missing = dir / "no/such/dir/frame.png";
    const std::string msg = what_of([&] { write_image(missing, test_image(4, 4, 4)); });
    EXPECT_NE(msg.find(missing), std::string::npos) << msg;
    EXPECT_TRUE(dir.entries().empty());

    // A bad image must not replace a good file, nor leave a temp beside it.
    write_image(dir / "keep.png", test_image(4, 4, 4));
    Image broken = test_image(4, 4, 4);
    broken.pixels.resize(5);
    const std::string msg2 = what_of([&] { write_image(dir / "keep.png", broken); });
    EXPECT_NE(msg2.find("keep.png"), std::string::npos) << msg2;
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"keep.png"});
    EXPECT_EQ(read_image(dir / "keep.png").width, 4);
}

TEST(ImageIo, ReadErrorsNameTheFile) {
    ScratchDir dir;
    const std::string msg = what_of([&] { read_image(dir / "absent.png"); });
    EXPECT_NE(msg.find("absent.png"), std::string::npos) << msg;
}

TEST(ImageIo, EnsureParentDirCreatesNestedDirectories) {
    ScratchDir dir;
    ensure_parent_dir(dir / "a/b/c/frame.png");
    EXPECT_TRUE(std::filesystem::is_directory(dir.path() / "a/b/c"));
    EXPECT_NO_THROW(ensure_parent_dir("frame.png"));  // no parent: nothing to do
}

TEST(ImageIo, Rgba8ConversionReplicatesGreyAndAddsAlpha) {
    Image grey;
    grey.width = 1;
    grey.height = 1;
    grey.channels = 1;
    grey.pixels = {0.5f};
    EXPECT_EQ(to_rgba8(grey), (std::vector<uint8_t>{128, 128, 128, 255}));
    EXPECT_EQ(to_unorm8(std::nanf("")), 0);
}

// to_unorm8 against the rule written out on its own (unorm8_reference.hpp), where rounding can
// go wrong: every level k/255 and every half-way point (k + 0.5)/255, i.e. j/510, and the floats
// just below and above each; then out of range, infinities and NaN.
TEST(ImageIo, ToUnorm8RoundsToNearestAtEveryHalfWayPointAndItsNeighbours) {
    int rounded_up = 0;
    for (int j = 0; j <= 510; ++j) {
        const float c = float(double(j) / 510.0);
        for (const float v : {std::nextafter(c, -1.0f), c, std::nextafter(c, 2.0f)}) {
            ASSERT_EQ(int(to_unorm8(v)), test::reference_unorm8(v)) << "v = " << v << " (" << j << "/510 and neighbours)";
            rounded_up += j % 2 == 1 && v == c && int(to_unorm8(v)) == (j + 1) / 2;
        }
    }
    EXPECT_EQ(rounded_up, 255) << "halves up: the float nearest each half-way point goes to the level above";
    EXPECT_EQ(int(to_unorm8(0.5f)), 128);
    EXPECT_EQ(int(to_unorm8(0.2f)), 51);
    EXPECT_EQ(int(to_unorm8(1.0f / 510.0f)), 1);
    EXPECT_EQ(int(to_unorm8(std::nextafter(1.0f / 510.0f, 0.0f))), 0);
    for (const float v : {-1.0f, -0.0f, 1.5f, 1e30f, std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity(), std::nanf("")})
        EXPECT_EQ(int(to_unorm8(v)), test::reference_unorm8(v)) << "v = " << v;
    EXPECT_EQ(test::reference_unorm8(std::numeric_limits<float>::infinity()), 255);
}

}  // namespace
}  // namespace pathlet
