#pragma once
// LDR-FLIP (Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström & Fairchild, "FLIP: A Difference
// Evaluator for Alternating Images", HPG 2020): the difference a viewer sees when flipping between
// two pictures, per pixel in [0, 1]. Written from the paper; every constant and step checked against
// the authors' reference implementation (github.com/NVlabs/flip, src/cpp/FLIP.h, LDR path):
//   colour   sRGB -> linear -> XYZ -> YCxCz (opponent space, D65 white); each channel filtered by
//            its contrast sensitivity (a Gaussian, the blue-yellow one a sum of two, sized by the
//            pixels per degree); back to linear RGB clamped to the gamut; L*a*b*; Hunt adjustment
//            (a, b scaled by 0.01 L); HyAB distance ^ qc (0.7); mapped to [0, 1] so that the
//            lower pc (0.4) of the largest distance (green to blue) fills [0, pt (0.95)]
//   features edges (1st derivative of a Gaussian of width w (0.082 degrees)) and points (2nd
//            derivative) of the achromatic channel; the larger of the two differences / sqrt 2, ^ qf (0.5)
//   FLIP     colour difference ^ (1 - feature difference)
// Borders repeat the edge pixel. Checked against the reference implementation (its FLIP.h built
// as a one-off oracle, mean summed in double) on its images/reference.png (1920x1080) and three
// perturbed copies (a 2-pixel shift with noise and a tint; a blur brightened by 10 levels;
// 16-level posterising): 0.2367597 / 0.1899695 / 0.0586666 there, 0.236760 / 0.189969 / 0.058667
// here; at 20 and 120 PPD 0.2920459 / 0.2097172 against 0.292046 / 0.209717. Their tool prints
// means ~6e-5 lower (it sums in float). Their test.png was not at hand, so their pair's 0.159691
// is not reproduced here: tests/quality/test_flip.cpp checks it given PATHLET_FLIP_IMAGES.
#include "image_io.hpp"

#include <cstdint>
#include <vector>

namespace pathlet::quality {

// The paper's default observer: 0.7 m from a 0.7 m wide monitor of 3840 pixels (≈ 67.02).
constexpr double kFlipPpd = 0.7 * (3840.0 / 0.7) * 3.14159265358979323846 / 180.0;

// The FLIP map of `test` against `reference` (same size, RGB(A) with sRGB-encoded values in
// [0, 1], clamped), one value a pixel, top row first. Throws std::invalid_argument on a size
// mismatch, fewer than 3 channels or ppd <= 0.
std::vector<float> flip_map(const Image& test, const Image& reference, double ppd = kFlipPpd);

// Its two parts per pixel (FLIP = colour ^ (1 - feature)), both in [0, 1].
struct FlipParts {
    std::vector<float> colour, feature;
};
FlipParts flip_parts(const Image& test, const Image& reference, double ppd = kFlipPpd);

// The map as a picture, through the magma colour map the FLIP authors show it in (black 0 ...
// purple ... orange ... light yellow 1); pixels outside `mask` (if given) dimmed to a third.
Image flip_image(const std::vector<float>& map, int width, int height, const std::vector<uint8_t>* mask = nullptr);

}  // namespace pathlet::quality
