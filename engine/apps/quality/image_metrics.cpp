#include "image_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace pathlet::quality {
namespace {

void require_same(const Image& a, const Image& b, size_t mask) {
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument("images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                    " and " + std::to_string(b.width) + "x" + std::to_string(b.height));
    if (a.channels < 3 || b.channels < 3) throw std::invalid_argument("images need RGB channels");
    if (mask != size_t(a.width) * size_t(a.height)) throw std::invalid_argument("mask and images differ in size");
}

// The normalised 1D Gaussian; the 2D window is its outer product (separable).
std::vector<double> gaussian() {
    std::vector<double> g(kSsimWindow);
    double sum = 0;
    for (int i = 0; i < kSsimWindow; ++i) {
        const double x = i - kSsimWindow / 2;
        sum += g[size_t(i)] = std::exp(-x * x / (2 * kSsimSigma * kSsimSigma));
    }
    for (double& v : g) v /= sum;
    return g;
}

// The 'valid' Gaussian filtering of `v`: out(x, y) for windows centred at (x, y) wholly inside.
std::vector<double> filter_valid(const std::vector<double>& v, int w, int h, const std::vector<double>& g) {
    const int r = kSsimWindow / 2;
    std::vector<double> rows(v.size(), 0.0), out(v.size(), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = r; x < w - r; ++x) {
            double s = 0;
            for (int k = -r; k <= r; ++k) s += g[size_t(k + r)] * v[size_t(y) * size_t(w) + size_t(x + k)];
            rows[size_t(y) * size_t(w) + size_t(x)] = s;
        }
    for (int y = r; y < h - r; ++y)
        for (int x = r; x < w - r; ++x) {
            double s = 0;
            for (int k = -r; k <= r; ++k) s += g[size_t(k + r)] * rows[size_t(y + k) * size_t(w) + size_t(x)];
            out[size_t(y) * size_t(w) + size_t(x)] = s;
        }
    return out;
}

}  // namespace

std::vector<float> luminance(const Image& img) {
    std::vector<float> l(size_t(img.width) * size_t(img.height));
    for (size_t i = 0; i < l.size(); ++i) {
        const float* p = &img.pixels[i * size_t(img.channels)];
        l[i] = img.channels >= 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0];
    }
    return l;
}

std::vector<float> ssim_map(const std::vector<float>& a, const std::vector<float>& b, int w, int h) {
    const size_t n = size_t(w) * size_t(h);
    if (a.size() != n || b.size() != n) throw std::invalid_argument("ssim_map: sizes differ");
    const std::vector<double> g = gaussian();
    std::vector<double> x(n), y(n), xx(n), yy(n), xy(n);
    for (size_t i = 0; i < n; ++i) {
        x[i] = a[i], y[i] = b[i];
        xx[i] = x[i] * x[i], yy[i] = y[i] * y[i], xy[i] = x[i] * y[i];
    }
    const std::vector<double> mx = filter_valid(x, w, h, g), my = filter_valid(y, w, h, g),
                              sxx = filter_valid(xx, w, h, g), syy = filter_valid(yy, w, h, g),
                              sxy = filter_valid(xy, w, h, g);
    const double c1 = kSsimK1 * kSsimK1, c2 = kSsimK2 * kSsimK2;  // dynamic range L = 1
    const int r = kSsimWindow / 2;
    std::vector<float> out(n, std::numeric_limits<float>::quiet_NaN());
    for (int yy_ = r; yy_ < h - r; ++yy_)
        for (int xx_ = r; xx_ < w - r; ++xx_) {
            const size_t i = size_t(yy_) * size_t(w) + size_t(xx_);
            const double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i], cov = sxy[i] - mx[i] * my[i];
            out[i] = float(((2 * mx[i] * my[i] + c1) * (2 * cov + c2)) /
                           ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2)));
        }
    return out;
}

ImageMetrics compare_images(const Image& test, const Image& ref, const std::vector<uint8_t>& mask, double ppd,
                            std::vector<float>* flip_out) {
    require_same(test, ref, mask.size());
    ImageMetrics m;
    const std::vector<float> s = ssim_map(luminance(test), luminance(ref), test.width, test.height);
    std::vector<float> flip = flip_map(test, ref, ppd);
    m.all_pixels = mask.size();
    for (size_t i = 0; i < mask.size(); ++i) {
        m.sum_flip_all += flip[i];
        if (!mask[i]) continue;
        m.sum_flip += flip[i];
        ++m.pixels;
        float worst = 0;
        for (int c = 0; c < 3; ++c) {
            const double d = double(test.pixels[i * size_t(test.channels) + size_t(c)]) -
                             double(ref.pixels[i * size_t(ref.channels) + size_t(c)]);
            m.sum_sq += d * d;
            worst = std::max(worst, float(std::fabs(d)));
        }
        m.over += worst * 255.0f > kOverLevels + 1e-3f;
        if (!std::isnan(s[i])) {
            m.sum_ssim += s[i];
            ++m.ssim_windows;
        }
    }
    if (flip_out) *flip_out = std::move(flip);
    return pool({m});
}

ImageMetrics pool(const std::vector<ImageMetrics>& frames) {
    ImageMetrics p;
    for (const ImageMetrics& f : frames) {
        p.pixels += f.pixels;
        p.ssim_windows += f.ssim_windows;
        p.sum_ssim += f.sum_ssim;
        p.sum_sq += f.sum_sq;
        p.over += f.over;
        p.sum_flip += f.sum_flip;
        p.sum_flip_all += f.sum_flip_all;
        p.all_pixels += f.all_pixels;
    }
    const double none = std::numeric_limits<double>::quiet_NaN();  // nothing to measure: n/a
    p.ssim = p.ssim_windows ? p.sum_ssim / double(p.ssim_windows) : none;
    const double mse = p.pixels ? p.sum_sq / (3.0 * double(p.pixels)) : none;
    p.rmse = std::sqrt(mse);
    p.psnr = !p.pixels ? none : mse > 0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
    p.share_over = p.pixels ? double(p.over) / double(p.pixels) : none;
    p.flip = p.pixels ? p.sum_flip / double(p.pixels) : none;
    p.flip_all = p.all_pixels ? p.sum_flip_all / double(p.all_pixels) : none;
    return p;
}

FlickerVsReference flicker_vs_reference(const std::vector<Image>& test, const std::vector<Image>& ref,
                                        const std::vector<std::vector<uint8_t>>& masks) {
    if (test.size() != ref.size() || test.size() != masks.size() || test.size() < 2)
        throw std::invalid_argument("flicker needs at least two frames of both pictures and their masks");
    FlickerAccumulator f;
    for (size_t k = 1; k < test.size(); ++k) f.add(test[k - 1], test[k], ref[k - 1], ref[k], masks[k - 1], masks[k]);
    return f.result();
}

void FlickerAccumulator::add(const Image& test_prev, const Image& test, const Image& ref_prev, const Image& ref,
                             const std::vector<uint8_t>& mask_prev, const std::vector<uint8_t>& mask) {
    for (const Image* im : {&test, &test_prev, &ref_prev}) require_same(*im, ref, mask.size());
    if (mask_prev.size() != mask.size()) throw std::invalid_argument("flicker: the masks differ in size");
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i] && !mask_prev[i]) continue;
        ++samples_;
        for (int c = 0; c < 3; ++c) {
            const auto at = [&](const Image& im) { return double(im.pixels[i * size_t(im.channels) + size_t(c)]); };
            const double dt = at(test) - at(test_prev), dr = at(ref) - at(ref_prev);
            excess_ += std::fabs(dt - dr);
            test_change_ += std::fabs(dt);
            reference_change_ += std::fabs(dr);
        }
    }
}

FlickerVsReference FlickerAccumulator::result() const {
    FlickerVsReference f;
    f.samples = samples_;
    const double n = 3.0 * double(std::max<size_t>(samples_, 1));
    f.excess = excess_ / n, f.test_change = test_change_ / n, f.reference_change = reference_change_ / n;
    return f;
}

AaFigures aa_figures(const Image& a, const Image& ref) {
    require_same(a, ref, size_t(a.width) * size_t(a.height));
    const auto level = [](const Image& im, int x, int y, int c) { return 255.0 * double(im.at(x, y, c)); };
    const auto covered = [&](const Image& im, int x, int y) {
        for (int c = 0; c < 3; ++c)
            if (std::fabs(level(im, x, y, c) - level(a, 0, 0, c)) > 8.0) return true;
        return false;
    };
    const auto lum = [&](int x, int y) { return (level(a, x, y, 0) + level(a, x, y, 1) + level(a, x, y, 2)) / 3.0; };
    AaFigures f;
    double sum = 0;
    size_t speckles = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (!covered(a, x, y) && !covered(ref, x, y)) continue;
            ++f.covered;
            for (int c = 0; c < 3; ++c) sum += std::pow(level(a, x, y, c) - level(ref, x, y, c), 2.0) / 3.0;
            if (x > 0 && y > 0 && x + 1 < a.width && y + 1 < a.height) {
                const double l = lum(x, y);
                speckles += lum(x - 1, y) - l > 60 && lum(x + 1, y) - l > 60 && lum(x, y - 1) - l > 60 &&
                            lum(x, y + 1) - l > 60;
            }
        }
    f.rms = f.covered ? std::sqrt(sum / double(f.covered)) : 0.0;
    f.speckle = f.covered ? double(speckles) / double(f.covered) : 0.0;
    return f;
}

Image difference_image(const Image& test, const Image& ref, const std::vector<uint8_t>& mask) {
    require_same(test, ref, mask.size());
    Image out;
    out.width = test.width;
    out.height = test.height;
    out.channels = 4;
    out.pixels.assign(mask.size() * 4, 1.0f);
    for (size_t i = 0; i < mask.size(); ++i) {
        float* o = &out.pixels[i * 4];
        if (!mask[i]) {
            o[0] = o[1] = o[2] = 0.9f;
            continue;
        }
        float d = 0;
        for (int c = 0; c < 3; ++c)
            d = std::max(d, std::fabs(test.pixels[i * size_t(test.channels) + size_t(c)] -
                                      ref.pixels[i * size_t(ref.channels) + size_t(c)]));
        const float e = std::min(d * 255.0f / 64.0f, 1.0f);  // 0 white ... 16/255 red ... 64/255 black
        o[0] = e < 0.25f ? 1.0f : 1.0f - (e - 0.25f) / 0.75f;
        o[1] = e < 0.25f ? 1.0f - e / 0.25f * 1.0f : 0.0f;
        o[2] = e < 0.125f ? 1.0f - e / 0.125f : 0.0f;
    }
    return out;
}

}  // namespace pathlet::quality
