#include "golden.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;

namespace pathlet {

namespace {

constexpr float kDiffGain = 8.0f;  // small errors become visible in the diff image

bool update_mode() {
    const char* v = std::getenv("PATHLET_UPDATE_GOLDENS");
    return v && std::string(v) == "1";
}

std::string fmt(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

Image quantized_to_8bit(Image img) {
    for (float& v : img.pixels) v = float(to_unorm8(v)) / 255.0f;
    img.is_float = false;
    return img;
}

// |a - b| x gain, opaque so the picture shows even where only alpha differs.
Image diff_image(const Image& a, const Image& b) {
    Image d = a;
    d.is_float = false;
    for (size_t i = 0; i < d.pixels.size(); ++i) d.pixels[i] = std::fabs(a.pixels[i] - b.pixels[i]) * kDiffGain;
    if (d.channels == 2 || d.channels == 4)
        for (size_t i = size_t(d.channels) - 1; i < d.pixels.size(); i += size_t(d.channels)) d.pixels[i] = 1.0f;
    return d;
}

OIIO::ImageBuf wrap(Image& img) {
    return OIIO::ImageBuf(OIIO::ImageSpec(img.width, img.height, img.channels, OIIO::TypeDesc::FLOAT),
                          img.pixels.data());
}

// Writes the images that explain a failure; returns a line saying where they are.
std::string dump(const std::string& golden_path, const Image& actual, const Image* expected) {
    const fs::path dir = golden_failure_dir();
    const std::string base = (dir / fs::path(golden_path).stem()).string();
    try {
        ensure_parent_dir(base + ".actual.png");
        write_image(base + ".actual.png", actual);
        std::string line = "\n  wrote " + base + ".actual.png";
        if (expected && expected->width == actual.width && expected->height == actual.height &&
            expected->channels == actual.channels) {
            write_image(base + ".expected.png", *expected);
            write_image(base + ".diff.png", diff_image(actual, *expected));
            line += ", .expected.png, .diff.png (|actual - expected| x" + fmt("%g", kDiffGain) + ")";
        } else if (expected) {
            write_image(base + ".expected.png", *expected);
            line += ", .expected.png";
        }
        return line;
    } catch (const std::exception& e) {
        return std::string("\n  could not write failure images: ") + e.what();
    }
}

::testing::AssertionResult write_golden(const Image& actual, const std::string& golden_path, const std::string& why) {
    try {
        ensure_parent_dir(golden_path);
        write_image(golden_path, actual);
    } catch (const std::exception& e) {
        return ::testing::AssertionFailure() << "PATHLET_UPDATE_GOLDENS=1 but " << e.what();
    }
    std::cout << "[golden] " << why << ": wrote " << golden_path << " (PATHLET_UPDATE_GOLDENS=1)\n";
    return ::testing::AssertionSuccess() << "wrote golden " << golden_path;
}

}  // namespace

std::string golden_failure_dir() {
    if (const char* dir = std::getenv("PATHLET_GOLDEN_FAILURE_DIR"); dir && *dir) return dir;
    std::error_code ec;
    fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ((ec ? fs::current_path() : exe.parent_path()) / "golden_failures").string();
}

::testing::AssertionResult matches_golden(const Image& actual, const std::string& golden_path, double fail_threshold,
                                          double max_failing_fraction) {
    if (has_nan(actual))
        return ::testing::AssertionFailure() << "actual image for " << golden_path << " contains NaN"
                                             << dump(golden_path, actual, nullptr);
    if (!fs::exists(golden_path)) {
        if (update_mode()) return write_golden(actual, golden_path, "new golden");
        return ::testing::AssertionFailure() << "golden " << golden_path
                                             << " is missing (run with PATHLET_UPDATE_GOLDENS=1 to create it)"
                                             << dump(golden_path, actual, nullptr);
    }

    Image expected;
    try {
        expected = read_image(golden_path);
    } catch (const std::exception& e) {
        return ::testing::AssertionFailure() << e.what();
    }
    Image a = expected.is_float ? actual : quantized_to_8bit(actual);
    if (a.width != expected.width || a.height != expected.height || a.channels != expected.channels) {
        if (update_mode()) return write_golden(actual, golden_path, "shape changed");
        return ::testing::AssertionFailure()
               << "golden " << golden_path << " is " << expected.width << "x" << expected.height << "x"
               << expected.channels << ", actual is " << a.width << "x" << a.height << "x" << a.channels
               << dump(golden_path, a, &expected);
    }

    OIIO::ImageBuf A = wrap(a), B = wrap(expected);
    const auto r = OIIO::ImageBufAlgo::compare(A, B, float(fail_threshold), float(fail_threshold));
    const size_t pixels = size_t(a.width) * size_t(a.height);
    const size_t allowed = size_t(std::floor(max_failing_fraction * double(pixels)));
    // r.error only means "some pixel failed" in OIIO 2.4; the budget decides here.
    const bool pass = std::isfinite(r.maxerror) && r.nfail <= allowed;

    std::string summary = "golden " + golden_path + ": mean error " + fmt("%.3g", r.meanerror) + ", max error " +
                          fmt("%.3g", r.maxerror) + " at (" + std::to_string(r.maxx) + "," + std::to_string(r.maxy) +
                          ") channel " + std::to_string(r.maxc) + ", " + std::to_string(r.nfail) + " of " +
                          std::to_string(pixels) + " pixels above " + fmt("%.4g", fail_threshold) + " (allowed " +
                          std::to_string(allowed) + ")";
    std::cout << "[golden] " << summary << "\n";
    if (pass) return ::testing::AssertionSuccess() << summary;
    if (update_mode()) return write_golden(actual, golden_path, "changed");
    return ::testing::AssertionFailure() << summary << dump(golden_path, a, &expected);
}

}  // namespace pathlet
