#include "frames/raw_frame.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace pathlet {

void divide_sums(std::vector<float>& sums, int factor) {
    // box_downsample's divisions, in its order: alpha-weighted colour, or the plain mean
    // where no sample has alpha; alpha's mean.
    const float n = float(factor * factor);
    for (size_t i = 0; i + 3 < sums.size(); i += 4) {
        float* p = &sums[i];
        const float a = p[3];
        for (int c = 0; c < 3; ++c) p[c] = a <= 0.0f ? p[c] / n : p[c] / a;
        p[3] = a / n;
    }
}

Image to_image(RawFrame&& raw) {
    Image img;
    img.width = raw.width;
    img.height = raw.height;
    img.channels = 4;
    img.is_float = true;
    const size_t w = size_t(raw.width), h = size_t(raw.height), row = w * 4;
    img.pixels.resize(row * h);
    using L = RawFrame::Layout;
    switch (raw.layout) {
        case L::Floats:
        case L::Sums:
            if (raw.data.size() < row * h) throw std::logic_error("to_image: short read-back");
            for (size_t y = 0; y < h; ++y)
                std::memcpy(&img.pixels[y * row], &raw.data[(h - 1 - y) * row], row * sizeof(float));
            break;
        case L::Depth:
            if (raw.data.size() < w * h) throw std::logic_error("to_image: short read-back");
            for (size_t y = 0; y < h; ++y) {
                const float* src = &raw.data[(h - 1 - y) * w];
                float* dst = &img.pixels[y * row];
                for (size_t x = 0; x < w; ++x) {
                    dst[4 * x] = dst[4 * x + 1] = dst[4 * x + 2] = src[x];
                    dst[4 * x + 3] = 1.0f;
                }
            }
            break;
        case L::Bytes: {
            if (raw.data.size() * sizeof(float) < row * h || !raw.table) throw std::logic_error("to_image: short read-back");
            const auto* bytes = reinterpret_cast<const uint8_t*>(raw.data.data());
            const ByteTable& t = *raw.table;
            for (size_t y = 0; y < h; ++y) {
                const uint8_t* src = bytes + (h - 1 - y) * row;
                float* dst = &img.pixels[y * row];
                for (size_t x = 0; x < row; x += 4)
                    for (size_t c = 0; c < 4; ++c) dst[x + c] = t[c][src[x + c]];
            }
            break;
        }
    }
    raw.data = {};  // the read-back's memory goes before the encoder needs its own
    if (raw.layout == L::Sums) divide_sums(img.pixels, raw.factor);
    else if (raw.factor > 1) img = box_downsample(img, raw.factor);
    return img;
}

}  // namespace pathlet
