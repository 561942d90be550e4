#include "image_probes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pathlet {

bool has_nan(const Image& img) {
    return std::any_of(img.pixels.begin(), img.pixels.end(), [](float v) { return std::isnan(v); });
}

float max_abs_difference(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels)
        throw std::invalid_argument("max_abs_difference: images of different shapes");
    float m = 0.0f;
    for (size_t i = 0; i < a.pixels.size(); ++i) m = std::max(m, std::fabs(a.pixels[i] - b.pixels[i]));
    return m;
}

double mean_luminance(const Image& img, PixelRect r) {
    const int x1 = r.w > 0 ? r.x + r.w : img.width, y1 = r.h > 0 ? r.y + r.h : img.height;
    if (r.x < 0 || r.y < 0 || x1 > img.width || y1 > img.height || x1 <= r.x || y1 <= r.y)
        throw std::out_of_range("mean_luminance: rect outside the " + std::to_string(img.width) + "x" +
                                std::to_string(img.height) + " image");
    double sum = 0;
    for (int y = r.y; y < y1; ++y)
        for (int x = r.x; x < x1; ++x)
            sum += img.channels >= 3 ? 0.2126 * img.at(x, y, 0) + 0.7152 * img.at(x, y, 1) + 0.0722 * img.at(x, y, 2)
                                     : double(img.at(x, y, 0));
    return sum / (double(x1 - r.x) * double(y1 - r.y));
}

size_t count_pixels_equal(const Image& img, glm::vec4 colour, float tol) {
    size_t count = 0;
    const int channels = std::min(img.channels, 4);
    for (size_t i = 0; i + size_t(img.channels) <= img.pixels.size(); i += size_t(img.channels)) {
        bool same = true;
        for (int c = 0; c < channels && same; ++c) same = std::fabs(img.pixels[i + size_t(c)] - colour[c]) <= tol;
        count += same ? 1 : 0;
    }
    return count;
}

}  // namespace pathlet
