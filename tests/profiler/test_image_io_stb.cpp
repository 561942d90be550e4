// The image backend of a build without OpenImageIO (engine/core/image_io_stb.cpp, the lean
// bundle's), compiled into this test in the full build: PNG round trips that agree with
// OpenImageIO's reading and writing of the same files, and EXR/TIFF/JPEG refused with the file
// and the reason, leaving nothing behind. (tests/bundle/test_lean_bundle.sh runs the lean build.)
#include "image_io_stb.hpp"
#include "error_text.hpp"
#include "scratch_dir.hpp"
#include "unorm8_reference.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>

namespace pathlet {
namespace {

Image ramp(int w, int h, int channels) {
    Image img;
    img.width = w;
    img.height = h;
    img.channels = channels;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c) img.pixels.push_back(float(x + 3 * y + 5 * c) / float(w + 3 * h + 15));
    img.pixels[0] = -0.5f;  // clamped to 0
    img.pixels[1] = 1.5f;   // clamped to 1
    return img;
}

std::string what_of(const std::function<void()>& f) { return pathlet::test::error_text<std::exception>(f); }

TEST(ImageIoStb, PngRoundTripMatchesOpenImageIoBothWays) {
    ScratchDir dir;
    for (int channels = 1; channels <= 4; ++channels) {
        const Image img = ramp(7, 5, channels);
        const std::string mine = dir / ("stb" + std::to_string(channels) + ".png");
        const std::string theirs = dir / ("oiio" + std::to_string(channels) + ".png");
        stb::write_png(mine, img);
        write_image(theirs, img);  // OpenImageIO in this build
        const Image a = stb::read_png(mine), b = read_image(mine), c = stb::read_png(theirs);
        ASSERT_EQ(a.width, 7);
        ASSERT_EQ(a.height, 5);
        ASSERT_EQ(a.channels, channels);
        EXPECT_FALSE(a.is_float);
        ASSERT_EQ(a.pixels.size(), img.pixels.size());
        for (size_t i = 0; i < img.pixels.size(); ++i) {
            EXPECT_FLOAT_EQ(a.pixels[i], float(test::reference_unorm8(img.pixels[i])) / 255.0f)
                << channels << " channels, value " << i;
            EXPECT_FLOAT_EQ(b.pixels[i], a.pixels[i]) << "OpenImageIO reads stb's file differently at " << i;
            EXPECT_FLOAT_EQ(c.pixels[i], a.pixels[i]) << "stb reads OpenImageIO's file differently at " << i;
        }
    }
    EXPECT_EQ(dir.entries().size(), 8u) << "no temporaries left";
}

TEST(ImageIoStb, NoExtensionWritesPng) {
    ScratchDir dir;
    stb::write_png(dir / "mask", ramp(4, 4, 1));
    std::ifstream in(dir / "mask", std::ios::binary);
    char magic[4] = {};
    in.read(magic, 4);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

TEST(ImageIoStb, ExrAndOtherFormatsAreRefusedNamingTheFileAndLeaveNothing) {
    ScratchDir dir;
    for (const auto& [name, why] : std::vector<std::pair<std::string, std::string>>{
             {"depth.exr", "this build has no EXR"},
             {"frame.tiff", "this build has no tiff"},
             {"frame.jpg", "this build reads and writes PNG only"}}) {
        const std::string path = dir / name;
        const std::string msg = what_of([&] { stb::write_png(path, ramp(4, 4, 4)); });
        EXPECT_NE(msg.find(path + ": cannot write image: " + why), std::string::npos) << msg;
        EXPECT_NE(msg.find("without OpenImageIO"), std::string::npos) << msg;
        EXPECT_TRUE(dir.entries().empty()) << name << " left a file";
    }
    write_image(dir / "real.exr", ramp(4, 4, 4));  // OpenImageIO writes it; stb still refuses to read it
    const std::string msg = what_of([&] { stb::read_png(dir / "real.exr"); });
    EXPECT_NE(msg.find(dir / "real.exr" + ": cannot read image: this build has no EXR"), std::string::npos) << msg;
}

TEST(ImageIoStb, BadAndMissingFilesAreErrorsNamingTheFile) {
    ScratchDir dir;
    std::ofstream(dir / "broken.png") << "\x89PNG\r\n\x1a\n not really";
    for (const std::string name : {"broken.png", "absent.png"}) {
        const std::string msg = what_of([&] { stb::read_png(dir / name); });
        EXPECT_NE(msg.find(dir / name), std::string::npos) << msg;
    }
    Image broken = ramp(4, 4, 4);
    broken.pixels.resize(5);
    const std::string msg = what_of([&] { stb::write_png(dir / "keep.png", broken); });
    EXPECT_NE(msg.find("keep.png: cannot write image: inconsistent image"), std::string::npos) << msg;
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"broken.png"});
}

}  // namespace
}  // namespace pathlet
