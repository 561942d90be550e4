// Cheap, robust image properties for tests ("the background is exactly the clear colour",
// "AO darkens the crease") to go with the few full-frame goldens. In namespace pathlet so
// unqualified calls find them through Image (ADL).
#pragma once

#include "image_io.hpp"

#include <glm/glm.hpp>

#include <cstddef>

namespace pathlet {

// Top-left origin, like Image rows. A width or height <= 0 means "to the image edge".
struct PixelRect {
    int x = 0, y = 0, w = 0, h = 0;
};

bool has_nan(const Image& img);
// Largest |a - b| over every channel of every pixel (same size and channels; throws otherwise).
float max_abs_difference(const Image& a, const Image& b);
// Rec. 709 luminance of RGB (channel 0 for grey images), averaged over the rect.
double mean_luminance(const Image& img, PixelRect rect = {});
// Pixels whose every channel is within tol of the colour's matching component.
size_t count_pixels_equal(const Image& img, glm::vec4 colour, float tol = 0.0f);

}  // namespace pathlet
