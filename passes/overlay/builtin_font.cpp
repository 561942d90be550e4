// The overlay's font when no font file can be used: stb_easy_font (Debian libstb-dev, public
// domain, no file, no texture) builds ASCII characters from axis-aligned unit quads on a
// 12-unit line. Each quad is scaled to the pixel size and rasterised with exact area coverage,
// so the text is anti-aliased at any size. Plain, but the time and the legend stay readable.
#include "text_raster.hpp"

#include <stb/stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace overlay {

namespace {
constexpr float kLineUnits = 12.0f;  // stb_easy_font's line height
constexpr float kAscentUnits = 8.0f;  // capitals span 0..7 with a unit-thick bottom stroke

struct Vertex {
    float x, y, z;
    unsigned char rgba[4];
};

// Adds the area of [x0,x1]x[y0,y1] (pixels) covering each pixel of `t`.
void cover(TextBitmap& t, std::vector<float>& acc, float x0, float y0, float x1, float y1) {
    const int px0 = std::max(0, int(std::floor(x0))), px1 = std::min(t.width, int(std::ceil(x1)));
    const int py0 = std::max(0, int(std::floor(y0))), py1 = std::min(t.height, int(std::ceil(y1)));
    for (int y = py0; y < py1; ++y) {
        const float h = std::min(y1, float(y + 1)) - std::max(y0, float(y));
        for (int x = px0; x < px1; ++x) {
            const float w = std::min(x1, float(x + 1)) - std::max(x0, float(x));
            if (w > 0 && h > 0) acc[size_t(y) * size_t(t.width) + size_t(x)] += w * h;
        }
    }
}
}  // namespace

TextBitmap render_builtin(const std::string& text, int pixel_size) {
    std::string ascii;
    for (char c : text) ascii += (c >= 32 && c < 127) ? c : '?';  // the font's table covers 32..126
    const float s = float(std::max(pixel_size, 1)) / kLineUnits;
    TextBitmap t;
    t.height = std::max(1, int(std::ceil(kLineUnits * s)));
    t.ascent = int(std::lround(kAscentUnits * s));
    t.width = std::max(1, int(std::ceil(float(stb_easy_font_width(ascii.data())) * s)));
    std::vector<float> acc(size_t(t.width) * size_t(t.height), 0.0f);
    std::vector<Vertex> quads(ascii.size() * 64 + 4);  // ~270 bytes a character, 4 vertices a quad
    const int n = stb_easy_font_print(0.0f, 0.0f, ascii.data(), nullptr, quads.data(), int(quads.size() * sizeof(Vertex)));
    for (int q = 0; q < n; ++q) {
        const Vertex& a = quads[size_t(q) * 4];
        const Vertex& c = quads[size_t(q) * 4 + 2];  // the opposite corner
        cover(t, acc, a.x * s, a.y * s, c.x * s, c.y * s);
    }
    t.coverage.resize(acc.size());
    std::transform(acc.begin(), acc.end(), t.coverage.begin(),
                   [](float v) { return uint8_t(std::lround(255.0f * std::min(v, 1.0f))); });
    return t;
}

}  // namespace overlay
