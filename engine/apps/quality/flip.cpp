#include "flip.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace pathlet::quality {
namespace {

using Vec3 = std::array<float, 3>;
constexpr float kPi = 3.14159265358979323846f;

// The paper's constants (section 4; NVlabs/flip FLIP.h names them gqc, gpc, gpt, gw, gqf).
constexpr float kQc = 0.7f, kPc = 0.4f, kPt = 0.95f, kW = 0.082f, kQf = 0.5f;

// Contrast sensitivity of each YCxCz channel as Gaussians a sqrt(pi / b) exp(-pi^2 x^2 / b) over
// x in degrees (the paper's table 1): achromatic, red-green, and blue-yellow as the sum of two.
constexpr float kCsfA[3] = {1.0f, 1.0f, 34.1f}, kCsfB[3] = {0.0047f, 0.0053f, 0.04f};
constexpr float kCsfA2 = 13.5f, kCsfB2 = 0.025f;  // the blue-yellow channel's second Gaussian

// sRGB (D65) primaries to XYZ, and the D65 white the opponent and Lab spaces are relative to.
constexpr float kToXyz[3][3] = {{10135552.0f / 24577794.0f, 8788810.0f / 24577794.0f, 4435075.0f / 24577794.0f},
                                {2613072.0f / 12288897.0f, 8788810.0f / 12288897.0f, 887015.0f / 12288897.0f},
                                {1425312.0f / 73733382.0f, 8788810.0f / 73733382.0f, 70074185.0f / 73733382.0f}};
constexpr Vec3 kWhite = {0.950428545f, 1.0f, 1.088900371f};

Vec3 mul(const float m[3][3], const Vec3& v) {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// XYZ to linear sRGB: the inverse of kToXyz, computed once.
struct FromXyz {
    float m[3][3];
    FromXyz() {
        const auto& a = kToXyz;
        const double det = double(a[0][0]) * (double(a[1][1]) * a[2][2] - double(a[1][2]) * a[2][1]) -
                           double(a[0][1]) * (double(a[1][0]) * a[2][2] - double(a[1][2]) * a[2][0]) +
                           double(a[0][2]) * (double(a[1][0]) * a[2][1] - double(a[1][1]) * a[2][0]);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {  // cofactor of (c, r) over the determinant
                const int r0 = (c + 1) % 3, r1 = (c + 2) % 3, c0 = (r + 1) % 3, c1 = (r + 2) % 3;
                m[r][c] = float((double(a[r0][c0]) * a[r1][c1] - double(a[r0][c1]) * a[r1][c0]) / det);
            }
    }
};
const FromXyz& from_xyz() {
    static const FromXyz f;
    return f;
}

float srgb_to_linear(float s) {
    s = std::clamp(s, 0.0f, 1.0f);
    return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f);
}

// CIE L*a*b* of linear RGB, then the Hunt adjustment: chroma fades with lightness (a, b * L / 100).
Vec3 hunt_lab(const Vec3& rgb) {
    const Vec3 xyz = mul(kToXyz, rgb);
    constexpr float d = 6.0f / 29.0f;
    Vec3 f;
    for (int i = 0; i < 3; ++i) {
        const float t = xyz[size_t(i)] / kWhite[size_t(i)];
        f[size_t(i)] = t > d * d * d ? std::cbrt(t) : t / (3.0f * d * d) + 4.0f / 29.0f;
    }
    const float l = 116.0f * f[1] - 16.0f;
    return {l, 0.01f * l * 500.0f * (f[0] - f[1]), 0.01f * l * 200.0f * (f[1] - f[2])};
}

// HyAB: city-block in lightness, Euclidean in the chromatic plane.
float hyab(const Vec3& p, const Vec3& q) {
    return std::fabs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]);
}

// One channel, `w` x `h`, filtered by the separable kernel `k` (odd length) along x then y, edges repeated.
std::vector<float> filter_x(const std::vector<float>& v, int w, int h, const std::vector<float>& k) {
    const int r = int(k.size()) / 2;
    std::vector<float> out(v.size());
    for (int y = 0; y < h; ++y) {
        const float* row = &v[size_t(y) * size_t(w)];
        for (int x = 0; x < w; ++x) {
            float s = 0;
            for (int i = -r; i <= r; ++i) s += k[size_t(i + r)] * row[std::clamp(x + i, 0, w - 1)];
            out[size_t(y) * size_t(w) + size_t(x)] = s;
        }
    }
    return out;
}
std::vector<float> filter_y(const std::vector<float>& v, int w, int h, const std::vector<float>& k) {
    const int r = int(k.size()) / 2;
    std::vector<float> out(v.size(), 0.0f);
    for (int y = 0; y < h; ++y) {
        float* o = &out[size_t(y) * size_t(w)];
        for (int i = -r; i <= r; ++i) {
            const float* row = &v[size_t(std::clamp(y + i, 0, h - 1)) * size_t(w)];
            const float kk = k[size_t(i + r)];
            for (int x = 0; x < w; ++x) o[x] += kk * row[x];
        }
    }
    return out;
}
std::vector<float> filter(const std::vector<float>& v, int w, int h, const std::vector<float>& kx,
                          const std::vector<float>& ky) {
    return filter_y(filter_x(v, w, h, kx), w, h, ky);
}

// The contrast sensitivity kernels, sampled at 1 / ppd degrees out to 3 sigma of the widest
// Gaussian. Y and Cx sum to 1; the blue-yellow channel's 2D kernel g1 g1' + g2 g2' is a sum of two
// separable ones, each 1D factor the square root of its Gaussian's weight, scaled so the 2D sum is 1.
struct CsfKernels {
    std::vector<float> y, cx, cz1, cz2;
};
CsfKernels csf_kernels(float ppd) {
    const float widest = std::max({kCsfB[0], kCsfB[1], kCsfB[2], kCsfB2});
    const int r = int(std::ceil(3.0f * std::sqrt(widest / (2.0f * kPi * kPi)) * ppd));
    CsfKernels k;
    const auto gauss = [](float x2, float a, float b) { return a * std::sqrt(kPi / b) * std::exp(-kPi * kPi * x2 / b); };
    float sy = 0, sx = 0, s1 = 0, s2 = 0;
    for (int i = -r; i <= r; ++i) {
        const float x2 = (float(i) / ppd) * (float(i) / ppd);
        k.y.push_back(gauss(x2, kCsfA[0], kCsfB[0]));
        k.cx.push_back(gauss(x2, kCsfA[1], kCsfB[1]));
        // sqrt(a sqrt(pi / b)) exp(-pi^2 x^2 / b): its outer product with itself is the 2D Gaussian.
        k.cz1.push_back(std::sqrt(gauss(0.0f, kCsfA[2], kCsfB[2])) * std::exp(-kPi * kPi * x2 / kCsfB[2]));
        k.cz2.push_back(std::sqrt(gauss(0.0f, kCsfA2, kCsfB2)) * std::exp(-kPi * kPi * x2 / kCsfB2));
        sy += k.y.back(), sx += k.cx.back(), s1 += k.cz1.back(), s2 += k.cz2.back();
    }
    const float sz = std::sqrt(s1 * s1 + s2 * s2);
    for (size_t i = 0; i < k.y.size(); ++i) k.y[i] /= sy, k.cx[i] /= sx, k.cz1[i] /= sz, k.cz2[i] /= sz;
    return k;
}

// The edge and point detectors: a Gaussian of standard deviation w/2 degrees in pixels, its 1st
// and 2nd derivatives; the Gaussian sums to 1, each derivative's positive weights to 1 and its
// negative ones to -1.
struct FeatureKernels {
    std::vector<float> g, dg, ddg;
};
FeatureKernels feature_kernels(float ppd) {
    const float sd = 0.5f * kW * ppd;
    const int r = int(std::ceil(3.0f * sd));
    FeatureKernels k;
    float sg = 0, dpos = 0, dneg = 0, ddpos = 0, ddneg = 0;
    for (int i = -r; i <= r; ++i) {
        const float x = float(i), g = std::exp(-x * x / (2.0f * sd * sd));
        const float dg = -x * g, ddg = (x * x / (sd * sd) - 1.0f) * g;
        k.g.push_back(g), k.dg.push_back(dg), k.ddg.push_back(ddg);
        sg += g;
        (dg > 0 ? dpos : dneg) += std::fabs(dg);
        (ddg > 0 ? ddpos : ddneg) += std::fabs(ddg);
    }
    for (size_t i = 0; i < k.g.size(); ++i) {
        k.g[i] /= sg;
        k.dg[i] /= k.dg[i] > 0 ? dpos : dneg;
        k.ddg[i] /= k.ddg[i] > 0 ? ddpos : ddneg;
    }
    return k;
}

// One picture in YCxCz, one channel a plane.
struct Opponent {
    std::vector<float> y, cx, cz;
};
Opponent opponent(const Image& im) {
    const size_t n = size_t(im.width) * size_t(im.height);
    Opponent o{std::vector<float>(n), std::vector<float>(n), std::vector<float>(n)};
    for (size_t i = 0; i < n; ++i) {
        const float* p = &im.pixels[i * size_t(im.channels)];
        const Vec3 xyz = mul(kToXyz, {srgb_to_linear(p[0]), srgb_to_linear(p[1]), srgb_to_linear(p[2])});
        const float x = xyz[0] / kWhite[0], y = xyz[1] / kWhite[1], z = xyz[2] / kWhite[2];
        o.y[i] = 116.0f * y - 16.0f, o.cx[i] = 500.0f * (x - y), o.cz[i] = 200.0f * (y - z);
    }
    return o;
}

// The CSF-filtered picture as Hunt-adjusted L*a*b*, the colour pipeline's last common step.
std::vector<Vec3> filtered_lab(const Opponent& o, int w, int h, const CsfKernels& k) {
    const std::vector<float> y = filter(o.y, w, h, k.y, k.y), cx = filter(o.cx, w, h, k.cx, k.cx),
                             cz1 = filter(o.cz, w, h, k.cz1, k.cz1), cz2 = filter(o.cz, w, h, k.cz2, k.cz2);
    std::vector<Vec3> lab(y.size());
    for (size_t i = 0; i < y.size(); ++i) {
        const float fy = (y[i] + 16.0f) / 116.0f;  // YCxCz back to XYZ (linear, unlike Lab) ...
        const Vec3 xyz = {(fy + cx[i] / 500.0f) * kWhite[0], fy * kWhite[1], (fy - (cz1[i] + cz2[i]) / 200.0f) * kWhite[2]};
        Vec3 rgb = mul(from_xyz().m, xyz);  // ... to linear RGB, clamped to the gamut
        for (float& c : rgb) c = std::clamp(c, 0.0f, 1.0f);
        lab[i] = hunt_lab(rgb);
    }
    return lab;
}

// Edge and point strength of the achromatic channel (YCxCz's Y back to [0, 1]).
struct Features {
    std::vector<float> edge, point;
};
Features features(const std::vector<float>& ycxcz_y, int w, int h, const FeatureKernels& k) {
    std::vector<float> a(ycxcz_y.size());
    for (size_t i = 0; i < a.size(); ++i) a[i] = (ycxcz_y[i] + 16.0f) / 116.0f;
    const std::vector<float> gx = filter_x(a, w, h, k.g), ex = filter_y(filter_x(a, w, h, k.dg), w, h, k.g),
                             ey = filter_y(gx, w, h, k.dg), px = filter_y(filter_x(a, w, h, k.ddg), w, h, k.g),
                             py = filter_y(gx, w, h, k.ddg);
    Features f{std::vector<float>(a.size()), std::vector<float>(a.size())};
    for (size_t i = 0; i < a.size(); ++i) f.edge[i] = std::hypot(ex[i], ey[i]), f.point[i] = std::hypot(px[i], py[i]);
    return f;
}

}  // namespace

FlipParts flip_parts(const Image& test, const Image& ref, double ppd_d) {
    if (test.width != ref.width || test.height != ref.height)
        throw std::invalid_argument("flip: images differ in size: " + std::to_string(test.width) + "x" +
                                    std::to_string(test.height) + " and " + std::to_string(ref.width) + "x" +
                                    std::to_string(ref.height));
    if (test.channels < 3 || ref.channels < 3) throw std::invalid_argument("flip: images need RGB channels");
    if (!(ppd_d > 0.0) || !std::isfinite(ppd_d))
        throw std::invalid_argument("flip: pixels per degree must be positive, not " + std::to_string(ppd_d));
    const float ppd = float(ppd_d);
    const int w = test.width, h = test.height;
    const Opponent ot = opponent(test), orf = opponent(ref);

    // Colour: HyAB between the filtered pictures, ^ qc, then mapped to [0, 1] around pc * cmax.
    const CsfKernels ck = csf_kernels(ppd);
    const std::vector<Vec3> lt = filtered_lab(ot, w, h, ck), lr = filtered_lab(orf, w, h, ck);
    const float cmax = std::pow(hyab(hunt_lab({0, 1, 0}), hunt_lab({0, 0, 1})), kQc), pccmax = kPc * cmax;
    // Features: the larger of the edge and point differences.
    const FeatureKernels fk = feature_kernels(ppd);
    const Features ft = features(ot.y, w, h, fk), fr = features(orf.y, w, h, fk);

    FlipParts p{std::vector<float>(lt.size()), std::vector<float>(lt.size())};
    for (size_t i = 0; i < lt.size(); ++i) {
        const float c = std::pow(hyab(lt[i], lr[i]), kQc);
        p.colour[i] = c < pccmax ? c * kPt / pccmax : kPt + (c - pccmax) / (cmax - pccmax) * (1.0f - kPt);
        const float fd = std::max(std::fabs(ft.edge[i] - fr.edge[i]), std::fabs(ft.point[i] - fr.point[i]));
        p.feature[i] = std::pow(fd / std::sqrt(2.0f), kQf);
    }
    return p;
}

std::vector<float> flip_map(const Image& test, const Image& ref, double ppd) {
    FlipParts p = flip_parts(test, ref, ppd);
    for (size_t i = 0; i < p.colour.size(); ++i) p.colour[i] = std::pow(p.colour[i], 1.0f - p.feature[i]);
    return std::move(p.colour);
}

Image flip_image(const std::vector<float>& map, int width, int height, const std::vector<uint8_t>* mask) {
    if (map.size() != size_t(width) * size_t(height) || (mask && mask->size() != map.size()))
        throw std::invalid_argument("flip_image: map, mask and size differ");
    // Magma (matplotlib's, CC0) at 0, 1/8, ..., 1; linear between.
    static constexpr float kMagma[9][3] = {{0.001462f, 0.000466f, 0.013866f}, {0.113094f, 0.065492f, 0.276784f},
                                           {0.316654f, 0.071690f, 0.485380f}, {0.512831f, 0.148179f, 0.507648f},
                                           {0.716387f, 0.214982f, 0.475290f}, {0.904281f, 0.319610f, 0.388137f},
                                           {0.986700f, 0.535582f, 0.382210f}, {0.996898f, 0.769591f, 0.534892f},
                                           {0.987053f, 0.991438f, 0.749504f}};
    Image out;
    out.width = width, out.height = height, out.channels = 4;
    out.pixels.assign(map.size() * 4, 1.0f);
    for (size_t i = 0; i < map.size(); ++i) {
        const float t = std::clamp(map[i], 0.0f, 1.0f) * 8.0f;
        const int k = std::min(int(t), 7);
        const float u = t - float(k), dim = mask && !(*mask)[i] ? 1.0f / 3.0f : 1.0f;
        for (int c = 0; c < 3; ++c)
            out.pixels[i * 4 + size_t(c)] = dim * (kMagma[k][c] + u * (kMagma[k + 1][c] - kMagma[k][c]));
    }
    return out;
}

}  // namespace pathlet::quality
