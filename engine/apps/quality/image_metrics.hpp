#pragma once
// Image fidelity against a reference picture (issue 42: transparency techniques against the exact
// reference), over a mask of the pixels that matter (those either picture covers):
//   ssim   windowed SSIM of Wang, Bovik, Sheikh & Simoncelli (IEEE TIP 2004) on luminance:
//          an 11x11 Gaussian window (sigma 1.5, normalised), K1 0.01, K2 0.03, dynamic range 1,
//          evaluated at every window that lies wholly inside the image (their 'valid' map),
//          averaged over the windows whose centre pixel is in the mask (not one window over
//          the whole frame, as some OIT comparisons did)
//   rmse   root mean square difference over the mask's pixels and the R, G, B channels (0..1)
//   psnr   10 log10(1 / mse) in dB (infinite for identical pictures)
//   share_over  share of the mask's pixels with a channel more than 8/255 apart
//   flip   mean LDR-FLIP (flip.hpp, Andersson et al. 2020) over the mask; flip_all over every pixel
// Luminance: Rec. 709 weights on the stored (sRGB-encoded) values, what a viewer sees.
#include "flip.hpp"
#include "image_io.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pathlet::quality {

// With nothing to measure (no window inside the image, an empty mask) a measure is NaN, which
// the command prints as n/a: never 1.0 or infinity for no data.
struct ImageMetrics {
    size_t pixels = 0;        // in the mask
    size_t ssim_windows = 0;  // windows averaged into ssim
    double ssim = 1.0, rmse = 0.0, psnr = 0.0, share_over = 0.0;
    bool ssim_measured() const { return ssim_windows > 0; }
    double sum_ssim = 0.0, sum_sq = 0.0;  // sums behind ssim and rmse, for pooling frames
    size_t over = 0;
    double flip = 0.0, flip_all = 0.0;    // mean LDR-FLIP over the mask, over every pixel
    double sum_flip = 0.0, sum_flip_all = 0.0;
    size_t all_pixels = 0;                // in the image
};

constexpr int kSsimWindow = 11;        // Wang et al.: 11 x 11
constexpr double kSsimSigma = 1.5;
constexpr double kSsimK1 = 0.01, kSsimK2 = 0.03;
constexpr float kOverLevels = 8.0f;    // share_over: more than 8 of 255 levels apart

// Rec. 709 luminance of an RGB(A) image, one float a pixel.
std::vector<float> luminance(const Image& img);
// The SSIM map: one value per pixel whose window lies inside the image (others NaN).
std::vector<float> ssim_map(const std::vector<float>& a, const std::vector<float>& b, int width, int height);
// Every measure of `test` against `reference` over `mask` (1 = measured; same size as the
// images), FLIP for a viewer at `ppd` pixels per degree (its map to `flip_out` if given).
// Throws std::invalid_argument when the sizes differ.
ImageMetrics compare_images(const Image& test, const Image& reference, const std::vector<uint8_t>& mask,
                            double ppd = kFlipPpd, std::vector<float>* flip_out = nullptr);
// Frames pooled: ssim over all windows, rmse, share and flip over all pixels.
ImageMetrics pool(const std::vector<ImageMetrics>& frames);

// Flicker against the reference: pictures change from frame to frame as the pathlets advance,
// so only the change beyond the reference's own is the technique's. Over the pixels either
// picture covers in either frame, and the R, G, B channels:
//   excess      mean |(T(t) - T(t-1)) - (R(t) - R(t-1))|
//   test_change, reference_change   mean |T(t) - T(t-1)| and mean |R(t) - R(t-1)|
struct FlickerVsReference {
    double excess = 0, test_change = 0, reference_change = 0;
    size_t samples = 0;  // pixel-frame pairs
};
// `masks[k]`: frame k's pixels either picture covers. Needs at least two frames of one size.
FlickerVsReference flicker_vs_reference(const std::vector<Image>& test, const std::vector<Image>& reference,
                                        const std::vector<std::vector<uint8_t>>& masks);
// The same, a pair of consecutive frames at a time (frames measured as they arrive).
class FlickerAccumulator {
public:
    void add(const Image& test_prev, const Image& test, const Image& ref_prev, const Image& ref,
             const std::vector<uint8_t>& mask_prev, const std::vector<uint8_t>& mask);
    FlickerVsReference result() const;

private:
    double excess_ = 0, test_change_ = 0, reference_change_ = 0;
    size_t samples_ = 0;
};

// The anti-aliasing figures of ../shared/tools/aa_metric.py, for a picture against a supersampled
// one of the same frame: rms (0..255 levels) over the pixels either picture covers (a channel more
// than 8 levels from the test picture's corner pixel, the background), and the share of covered
// pixels that are isolated dark speckles (luminance, the mean of R, G, B, lower by more than 60
// levels than all four neighbours'; a pixel on the border has no four).
struct AaFigures {
    double rms = 0, speckle = 0;
    size_t covered = 0;
};
AaFigures aa_figures(const Image& test, const Image& reference);

// The per-pixel difference as a heat map: white 0, through yellow and red (16/255) to black
// (64/255 and more) on measured pixels, light grey elsewhere.
Image difference_image(const Image& test, const Image& reference, const std::vector<uint8_t>& mask);

}  // namespace pathlet::quality
