// The fidelity measures of `pathlet quality --reference` against independent CPU
// computations on small synthetic images: SSIM by a direct sum over each 11x11 Gaussian window
// (no separable filtering), RMSE/PSNR/share by hand, the flicker beyond the reference's own by
// construction. Identical images give ssim 1 and rmse 0; known shifts give known numbers.
#include "image_metrics.hpp"

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <random>

using namespace pathlet;
using namespace pathlet::quality;

namespace {

Image grey(int w, int h, const std::function<float(int, int)>& f) {
    Image im;
    im.width = w, im.height = h, im.channels = 4;
    im.pixels.resize(size_t(w) * size_t(h) * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            for (int c = 0; c < 3; ++c) im.at(x, y, c) = f(x, y);
            im.at(x, y, 3) = 1.0f;
        }
    return im;
}

Image noise(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Image im = grey(w, h, [](int, int) { return 0.0f; });
    for (size_t i = 0; i < im.pixels.size(); ++i) im.pixels[i] = (i % 4 == 3) ? 1.0f : std::round(u(rng) * 255) / 255;
    return im;
}

std::vector<uint8_t> all(const Image& im) { return std::vector<uint8_t>(size_t(im.width) * size_t(im.height), 1); }

// SSIM straight from Wang et al.'s definition: for each window wholly inside the image, the
// Gaussian-weighted means, variances and covariance summed directly over its 121 pixels.
double naive_ssim(const Image& a, const Image& b, const std::vector<uint8_t>& mask) {
    auto lum = [](const Image& im, int x, int y) {
        return 0.2126 * im.at(x, y, 0) + 0.7152 * im.at(x, y, 1) + 0.0722 * im.at(x, y, 2);
    };
    double w[11][11], sum = 0;
    for (int j = 0; j < 11; ++j)
        for (int i = 0; i < 11; ++i) sum += w[j][i] = std::exp(-((i - 5) * (i - 5) + (j - 5) * (j - 5)) / (2 * 1.5 * 1.5));
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    double total = 0;
    size_t n = 0;
    for (int y = 5; y < a.height - 5; ++y)
        for (int x = 5; x < a.width - 5; ++x) {
            if (!mask[size_t(y) * size_t(a.width) + size_t(x)]) continue;
            double mx = 0, my = 0;
            for (int j = 0; j < 11; ++j)
                for (int i = 0; i < 11; ++i) {
                    mx += w[j][i] / sum * lum(a, x + i - 5, y + j - 5);
                    my += w[j][i] / sum * lum(b, x + i - 5, y + j - 5);
                }
            double vx = 0, vy = 0, cov = 0;
            for (int j = 0; j < 11; ++j)
                for (int i = 0; i < 11; ++i) {
                    const double dx = lum(a, x + i - 5, y + j - 5) - mx, dy = lum(b, x + i - 5, y + j - 5) - my;
                    vx += w[j][i] / sum * dx * dx, vy += w[j][i] / sum * dy * dy, cov += w[j][i] / sum * dx * dy;
                }
            total += (2 * mx * my + c1) * (2 * cov + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
            ++n;
        }
    return total / double(n);
}

}  // namespace

TEST(ImageMetrics, IdenticalImagesAreSsimOneAndRmseZero) {
    const Image a = noise(40, 30, 1);
    const ImageMetrics m = compare_images(a, a, all(a));
    EXPECT_NEAR(m.ssim, 1.0, 1e-9);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_TRUE(std::isinf(m.psnr));
    EXPECT_EQ(m.share_over, 0.0);
    EXPECT_EQ(m.pixels, 1200u);
    EXPECT_EQ(m.ssim_windows, size_t(30) * 20);  // windows wholly inside: (40 - 10) x (30 - 10)
}

TEST(ImageMetrics, SsimIsWangsWindowedMeanAsADirectSumGivesIt) {
    const Image a = noise(40, 30, 2);
    Image b = a;  // a blurred, brightened copy: structure, contrast and luminance all change
    for (int y = 0; y < a.height; ++y)
        for (int x = 1; x < a.width; ++x)
            for (int c = 0; c < 3; ++c) b.at(x, y, c) = std::min(1.0f, 0.5f * (a.at(x, y, c) + a.at(x - 1, y, c)) + 0.05f);
    const ImageMetrics m = compare_images(b, a, all(a));
    const double want = naive_ssim(b, a, all(a));
    EXPECT_NEAR(m.ssim, want, 1e-6);
    EXPECT_LT(m.ssim, 0.9);
    EXPECT_GT(m.ssim, 0.1);
    // Only windows whose centre is in the mask count: the left half alone gives its own mean.
    std::vector<uint8_t> left = all(a);
    for (int y = 0; y < a.height; ++y)
        for (int x = a.width / 2; x < a.width; ++x) left[size_t(y) * size_t(a.width) + size_t(x)] = 0;
    EXPECT_NEAR(compare_images(b, a, left).ssim, naive_ssim(b, a, left), 1e-6);
    EXPECT_NE(compare_images(b, a, left).ssim, m.ssim);
}

// Stripes one pixel wide, shifted by one pixel: every pixel is a full level apart (rmse 1,
// psnr 0 dB, all over 8/255) and the structure is inverted (ssim near -1).
TEST(ImageMetrics, AOnePixelShiftOfStripes) {
    const Image a = grey(32, 24, [](int x, int) { return float(x % 2); });
    const Image b = grey(32, 24, [](int x, int) { return float((x + 1) % 2); });
    const ImageMetrics m = compare_images(b, a, all(a));
    EXPECT_NEAR(m.rmse, 1.0, 1e-9);
    EXPECT_NEAR(m.psnr, 0.0, 1e-9);
    EXPECT_NEAR(m.share_over, 1.0, 1e-12);
    EXPECT_NEAR(m.ssim, naive_ssim(b, a, all(a)), 1e-6);
    EXPECT_LT(m.ssim, -0.9);
}

// A ramp brightened by 4 and by 9 levels: rmse 4/255 and 9/255, psnr 20 log10(255/4) and
// 20 log10(255/9); none and all of the pixels over 8/255.
TEST(ImageMetrics, AKnownBrightnessShift) {
    const Image a = grey(64, 16, [](int x, int) { return float(x + 100) / 255.0f; });
    for (int levels : {4, 9}) {
        const Image b = grey(64, 16, [&](int x, int) { return float(x + 100 + levels) / 255.0f; });
        const ImageMetrics m = compare_images(b, a, all(a));
        EXPECT_NEAR(m.rmse, levels / 255.0, 1e-6) << levels;
        EXPECT_NEAR(m.psnr, 20.0 * std::log10(255.0 / levels), 1e-4) << levels;
        EXPECT_EQ(m.share_over, levels > 8 ? 1.0 : 0.0) << levels;
        EXPECT_NEAR(m.ssim, naive_ssim(b, a, all(a)), 1e-6) << levels;
        EXPECT_LT(m.ssim, 1.0) << levels;
    }
}

// Pixels outside the mask do not count; frames pool by their pixels and windows.
TEST(ImageMetrics, OnlyTheMaskCountsAndFramesPool) {
    const Image a = grey(30, 20, [](int, int) { return 0.5f; });
    Image b = a;
    b.at(3, 3, 0) = 1.0f;  // one pixel off, outside the mask
    std::vector<uint8_t> mask = all(a);
    mask[3 * 30 + 3] = 0;
    EXPECT_EQ(compare_images(b, a, mask).rmse, 0.0);
    EXPECT_EQ(compare_images(b, a, mask).pixels, 599u);
    const ImageMetrics off = compare_images(b, a, all(a)), same = compare_images(a, a, all(a));
    const ImageMetrics p = pool({off, same});
    EXPECT_EQ(p.pixels, 1200u);
    EXPECT_NEAR(p.rmse, std::sqrt(0.25 / (3.0 * 1200)), 1e-9);  // one channel 0.5 apart in 1200 pixels
    EXPECT_NEAR(p.share_over, 1.0 / 1200, 1e-12);
}

// The flicker beyond the reference's own: a test that follows the reference exactly has none
// however much the reference changes; one that alternates by d on top of it has exactly d.
TEST(ImageMetrics, FlickerIsTheChangeBeyondTheReferences) {
    std::vector<Image> ref, same, jitter;
    std::vector<std::vector<uint8_t>> masks;
    const float d = 6.0f / 255.0f;
    for (int k = 0; k < 4; ++k) {
        ref.push_back(grey(16, 8, [&](int x, int) { return float((x + 3 * k) % 16) / 20.0f; }));
        same.push_back(ref.back());
        jitter.push_back(grey(16, 8, [&](int x, int) { return float((x + 3 * k) % 16) / 20.0f + (k % 2) * d; }));
        masks.push_back(all(ref.back()));
    }
    const FlickerVsReference f0 = flicker_vs_reference(same, ref, masks);
    EXPECT_EQ(f0.excess, 0.0);
    EXPECT_GT(f0.reference_change, 0.05);
    EXPECT_EQ(f0.test_change, f0.reference_change);
    const FlickerVsReference f1 = flicker_vs_reference(jitter, ref, masks);
    EXPECT_NEAR(f1.excess, d, 1e-6);
    EXPECT_EQ(f1.samples, size_t(3) * 128);
    EXPECT_THROW(flicker_vs_reference({ref[0]}, {ref[0]}, {masks[0]}), std::invalid_argument);
}

TEST(ImageMetrics, SizesThatDifferAreAnError) {
    const Image a = noise(20, 20, 3), b = noise(21, 20, 3);
    EXPECT_THROW(compare_images(a, b, all(a)), std::invalid_argument);
    EXPECT_THROW(compare_images(a, a, std::vector<uint8_t>(5, 1)), std::invalid_argument);
}

// The heat map: white where equal, red at 16/255, black from 64/255, light grey off the mask.
TEST(ImageMetrics, DifferenceImageColours) {
    const Image a = grey(4, 1, [](int, int) { return 0.2f; });
    const Image b = grey(4, 1, [](int x, int) { return 0.2f + (x == 1 ? 16.0f : x == 2 ? 64.0f : 0.0f) / 255.0f; });
    std::vector<uint8_t> mask = {1, 1, 1, 0};
    const Image h = difference_image(b, a, mask);
    auto px = [&](int x) { return glm::vec3(h.at(x, 0, 0), h.at(x, 0, 1), h.at(x, 0, 2)); };
    EXPECT_EQ(px(0), glm::vec3(1.0f));
    EXPECT_NEAR(glm::length(px(1) - glm::vec3(1, 0, 0)), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::length(px(2)), 0.0f, 1e-4f);
    EXPECT_EQ(px(3), glm::vec3(0.9f));
}
