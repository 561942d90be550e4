#include "frames/raw_frame.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace pathlet {

PackedPixels PackedPixels::own(std::vector<uint8_t> bytes) {
    auto keep = std::make_shared<const std::vector<uint8_t>>(std::move(bytes));
    PackedPixels p;
    p.data = keep->data();
    p.size = keep->size();
    p.keep = std::move(keep);
    return p;
}

int RawFrame::bytes_per_pixel() const {
    switch (layout) {
        case Layout::Floats: return channels * (half ? 2 : 4);
        case Layout::Depth: return 4;
        case Layout::Bytes: return 4;
        case Layout::Sums: return 16;
    }
    return 16;
}

float half_to_float(uint16_t h) {
    const uint32_t sign = uint32_t(h & 0x8000u) << 16, exp = (h >> 10) & 0x1fu, mant = h & 0x3ffu;
    uint32_t bits;
    if (exp == 0) {  // zero or denormal: mant * 2^-24, exact in a float
        const float f = std::ldexp(float(mant), -24);
        std::memcpy(&bits, &f, 4);
        bits |= sign;
    } else if (exp == 31) {
        bits = sign | 0x7f800000u | (mant << 13);
    } else {
        bits = sign | ((exp + 112u) << 23) | (mant << 13);
    }
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

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

namespace {

// One packed row of `channels` halfs or floats as RGBA floats, as GL widens them.
void widen_row(const uint8_t* src, float* dst, size_t w, int channels, bool half) {
    if (channels == 4 && !half) {
        std::memcpy(dst, src, w * 16);
        return;
    }
    const size_t ch = size_t(channels);
    for (size_t x = 0; x < w; ++x) {
        float* d = dst + 4 * x;
        for (size_t c = 0; c < 4; ++c) {
            if (c >= ch) {
                d[c] = c == 3 ? 1.0f : 0.0f;
            } else if (half) {
                uint16_t v;
                std::memcpy(&v, src + (x * ch + c) * 2, 2);
                d[c] = half_to_float(v);
            } else {
                std::memcpy(&d[c], src + (x * ch + c) * 4, 4);
            }
        }
    }
}

}  // namespace

Image to_image(RawFrame&& raw) {
    Image img;
    img.width = raw.width;
    img.height = raw.height;
    img.channels = 4;
    img.is_float = true;
    const size_t w = size_t(raw.width), h = size_t(raw.height), row = w * 4, stride = raw.row_bytes();
    if (!raw.data.data || raw.data.size < stride * h || (raw.layout == RawFrame::Layout::Bytes && !raw.table))
        throw std::logic_error("to_image: short read-back");
    img.pixels.resize(row * h);
    using L = RawFrame::Layout;
    for (size_t y = 0; y < h; ++y) {
        const uint8_t* src = raw.data.data + (h - 1 - y) * stride;  // GL rows are bottom-up
        float* dst = &img.pixels[y * row];
        switch (raw.layout) {
            case L::Floats: widen_row(src, dst, w, raw.channels, raw.half); break;
            case L::Sums: widen_row(src, dst, w, 4, false); break;
            case L::Depth:
                for (size_t x = 0; x < w; ++x) {
                    std::memcpy(&dst[4 * x], src + 4 * x, 4);
                    dst[4 * x + 1] = dst[4 * x + 2] = dst[4 * x];
                    dst[4 * x + 3] = 1.0f;
                }
                break;
            case L::Bytes: {
                const ByteTable& t = *raw.table;
                for (size_t x = 0; x < row; x += 4)
                    for (size_t c = 0; c < 4; ++c) dst[x + c] = t[c][src[x + c]];
                break;
            }
        }
    }
    raw.data = {};  // the pack buffer goes back to the ring before the encoder needs its own memory
    if (raw.layout == L::Sums) divide_sums(img.pixels, raw.factor);
    else if (raw.factor > 1) img = box_downsample(img, raw.factor);
    return img;
}

}  // namespace pathlet
