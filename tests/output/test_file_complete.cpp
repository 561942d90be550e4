// image_file_complete (frames/file_complete.hpp): a frame cut short by a full disk is never
// renamed into place. Whole PNG, EXR, TIFF and JPEG files pass; the same files cut at any length
// fail; the check reads their structure, not their pixels.
#include "frames/file_complete.hpp"
#include "image_io.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace pathlet {
namespace {

namespace fs = std::filesystem;

fs::path scratch() {
    fs::path p = fs::path(PATHLET_TEST_BINARY_DIR) / "file_complete";
    fs::create_directories(p);
    return p;
}

Image gradient(int w, int h) {
    Image img;
    img.width = w;
    img.height = h;
    img.pixels.resize(size_t(w) * size_t(h) * 4);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float((i * 7919) % 1000) / 999.0f;
    return img;
}

std::string bytes_of(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expect_cuts_detected(const std::string& ext) {
    const fs::path whole = scratch() / ("whole" + ext), cut = scratch() / ("cut" + ext);
    write_image(whole.string(), gradient(97, 61));  // odd sizes: EXR's last chunk is a short one
    ASSERT_TRUE(image_file_complete(whole.string())) << ext;
    const std::string b = bytes_of(whole);
    for (size_t len : {size_t(0), size_t(8), size_t(100), b.size() / 3, b.size() / 2, b.size() - 13, b.size() - 1}) {
        std::ofstream(cut, std::ios::binary | std::ios::trunc).write(b.data(), std::streamsize(len));
        EXPECT_FALSE(image_file_complete(cut.string())) << ext << " cut to " << len << " of " << b.size() << " bytes";
    }
}

TEST(FileComplete, APngCutShortIsIncomplete) { expect_cuts_detected(".png"); }
TEST(FileComplete, AnExrCutShortIsIncomplete) { expect_cuts_detected(".exr"); }
TEST(FileComplete, ATiffOrJpegCutShortIsIncomplete) {
    expect_cuts_detected(".tif");
    expect_cuts_detected(".jpg");
}

TEST(FileComplete, TheCheckReadsTheStructureNotThePixels) {
    // Garbage in the middle of the pixel data, the structure intact: whole (a decode would fail
    // or not, but it is not asked for: the check costs a few reads, not a second decode).
    for (const std::string ext : {".exr", ".tif", ".png"}) {
        const fs::path p = scratch() / ("garbage" + ext);
        write_image(p.string(), gradient(97, 61));
        std::string b = bytes_of(p);
        for (size_t i = b.size() / 3; i < b.size() / 2; ++i) b[i] = char(i * 131);
        std::ofstream(p, std::ios::binary | std::ios::trunc) << b;
        EXPECT_TRUE(image_file_complete(p.string())) << ext;
        if (ext == ".exr") { EXPECT_ANY_THROW(read_image(p.string())) << "the garbage is not decodable: this proves no decode"; }
    }
}

TEST(FileComplete, AnExrWhoseOffsetTableWasNeverFilledIsIncomplete) {
    // OpenEXR writes the chunk offsets last: a failed final write leaves them zero.
    const fs::path p = scratch() / "zeros.exr";
    write_image(p.string(), gradient(32, 40));
    std::string b = bytes_of(p);
    // The header's last attribute (OpenEXR sorts them by name), "screenWindowWidth\0float\0"
    // with a 4-byte size and a 4-byte value, then the empty name that ends the header.
    const size_t last = b.rfind("screenWindowWidth");
    ASSERT_NE(last, std::string::npos);
    const size_t header_end = last + 18 + 6 + 4 + 4;
    ASSERT_EQ(b[header_end], '\0');
    std::fill(b.begin() + long(header_end) + 1, b.begin() + long(header_end) + 1 + 8, '\0');  // the first offset
    std::ofstream(p, std::ios::binary | std::ios::trunc) << b;
    EXPECT_FALSE(image_file_complete(p.string()));
}

}  // namespace
}  // namespace pathlet
