// Moment-based OIT (mboit_moments -> mboit_accum -> oit_composite) on real GL (llvmpipe): the
// picture against a CPU MBOIT in double precision of the very fragments fill_list stores for
// the same lines (a 3x3 solve with pivoting and Lagrange weights, not the shader's L D L^T and
// Christoffel weights), single-layer pixels against the exact resolve, layered ones nearer it than an
// order-blind blend of the same sums, and a golden of graphs/variant2_mboit.json. With 6 and 8
// power moments and 2, 3, 4 trigonometric ones (moment_form power6, power8, trig2..trig4): the
// same against a CPU reference in double that reaches the shader's result by other means (roots
// by bisection between the derivative's roots, or as minima of |q| on the unit circle; weights
// from the Vandermonde system), single fragments and lone lines exact, and on the small phantom
// more power moments nearer variant2_exact. Layers from the near plane on (the camera inside
// the data's bounding sphere) put the trigonometric forms' roots into the wrapping zone.
#include "camera.hpp"
#include "executor.hpp"
#include "frame_capture.hpp"
#include "golden.hpp"
#include "oit_lists.hpp"
#include "straight_lines.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <complex>
#include <cmath>
#include <cstring>
#include <vector>

using namespace pathlet;

namespace {

const std::string kSrc = PATHLET_SOURCE_DIR;
const std::string kHere = PATHLET_TEST_SOURCE_DIR;
const glm::ivec2 kSmall{160, 120};

struct Lists : OitLists {
    Image exact, mboit;         // top-down
    Camera camera;
};

Lists render_lists(const std::string& graph, std::vector<std::string> sets, const Scene& scene = helix_bundle_scene(),
                   const std::string& camera_path = "") {
    RenderOptions opt;
    opt.graph_path = graph;
    opt.sets = std::move(sets);
    opt.size = kSmall;
    opt.time.start = opt.time.end = 6.0;
    opt.warmup = 0;
    opt.write_images = false;
    opt.quiet = true;
    Lists l;
    opt.camera_path = camera_path;
    l.camera = camera_path.empty() ? frame_bounds(scene.bounds(), opt.size)
                                   : CameraPath::load(camera_path).at(opt.time.start, scene.bounds(), opt.size);
    render(test_runtime(), scene, opt, [&](const Executor& ex, size_t) {
        static_cast<OitLists&>(l) = read_oit_lists(ex);
        l.exact = read_resource(ex.texture("exact"));
        l.mboit = read_resource(ex.texture("mboit"));
    });
    return l;
}


// Transmittance in front of z0 from 4 moments (b0, b1..b4), the paper's way in double.
double transmittance4(double b0, const std::array<double, 4>& b, double z0, double bias = 5e-7, double beta = 0.1) {
    if (b0 <= 1e-6) return 1.0;
    double m[5] = {1.0};
    const double uniform[5] = {1.0, 0.0, 1.0 / 3.0, 0.0, 1.0 / 5.0};
    for (int k = 1; k <= 4; ++k) m[k] = (1.0 - bias) * b[k - 1] / b0 + bias * uniform[k];
    // H c = (1, z0, z0^2) by Gaussian elimination with partial pivoting.
    double a[3][4] = {{m[0], m[1], m[2], 1.0}, {m[1], m[2], m[3], z0}, {m[2], m[3], m[4], z0 * z0}};
    for (int c = 0; c < 3; ++c) {
        int piv = c;
        for (int r = c + 1; r < 3; ++r)
            if (std::abs(a[r][c]) > std::abs(a[piv][c])) piv = r;
        std::swap(a[c], a[piv]);
        for (int r = c + 1; r < 3; ++r) {
            const double f = a[r][c] / a[c][c];
            for (int k = c; k < 4; ++k) a[r][k] -= f * a[c][k];
        }
    }
    double c[3];
    for (int r = 2; r >= 0; --r) {
        double s = a[r][3];
        for (int k = r + 1; k < 3; ++k) s -= a[r][k] * c[k];
        c[r] = s / a[r][r];
    }
    const double disc = std::sqrt(std::max(c[1] * c[1] - 4.0 * c[2] * c[0], 0.0));
    const double z[3] = {z0, (-c[1] - disc) / (2.0 * c[2]), (-c[1] + disc) / (2.0 * c[2])};
    const double f[3] = {beta, z[1] < z0 ? 1.0 : 0.0, z[2] < z0 ? 1.0 : 0.0};
    // E[p] for the Lagrange polynomial through (z_i, f_i): sum_i f_i E[L_i].
    double share = 0.0;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        const double den = (z[i] - z[j]) * (z[i] - z[k]);
        // L_i(x) = (x^2 - (z_j + z_k) x + z_j z_k) / den
        share += f[i] * (m[2] - (z[j] + z[k]) * m[1] + z[j] * z[k]) / den;
    }
    return std::clamp(std::exp(-b0 * share), 0.0, 1.0);
}

// The real roots of c[0] + c[1] x + .. (all real: a kernel polynomial's), each by bisection
// between neighbouring roots of the derivative (Rolle) and a Cauchy bound.
std::vector<double> real_roots(const std::vector<double>& c) {
    const size_t k = c.size() - 1;
    if (k == 1) return {-c[0] / c[1]};
    std::vector<double> d(k);
    for (size_t i = 1; i <= k; ++i) d[i - 1] = double(i) * c[i];
    double bound = 1.0;
    for (size_t i = 0; i < k; ++i) bound = std::max(bound, 1.0 + std::abs(c[i] / c[k]));
    std::vector<double> pts = real_roots(d);
    pts.insert(pts.begin(), -bound);
    pts.push_back(bound);
    auto p = [&](double x) {
        double v = 0.0;
        for (size_t i = k + 1; i-- > 0;) v = v * x + c[i];
        return v;
    };
    std::vector<double> roots;
    for (size_t i = 0; i + 1 < pts.size(); ++i) {
        double a = pts[i], b = pts[i + 1];
        if ((p(a) > 0) == (p(b) > 0)) continue;
        for (int it = 0; it < 200; ++it) {
            const double m = 0.5 * (a + b);
            ((p(m) > 0) == (p(a) > 0) ? a : b) = m;
        }
        roots.push_back(0.5 * (a + b));
    }
    return roots;
}

// x = A^-1 y by Gaussian elimination with partial pivoting (real or complex).
template <class T>
std::vector<T> solve(std::vector<std::vector<T>> a, std::vector<T> y) {
    const size_t n = y.size();
    for (size_t c = 0; c < n; ++c) {
        size_t piv = c;
        for (size_t r = c + 1; r < n; ++r)
            if (std::abs(a[r][c]) > std::abs(a[piv][c])) piv = r;
        std::swap(a[c], a[piv]);
        std::swap(y[c], y[piv]);
        for (size_t r = c + 1; r < n; ++r) {
            const T f = a[r][c] / a[c][c];
            for (size_t k = c; k < n; ++k) a[r][k] -= f * a[c][k];
            y[r] -= f * y[c];
        }
    }
    std::vector<T> x(n);
    for (size_t r = n; r-- > 0;) {
        T s = y[r];
        for (size_t k = r + 1; k < n; ++k) s -= a[r][k] * x[k];
        x[r] = s / a[r][r];
    }
    return x;
}

// Transmittance in front of z0 from 2n power moments (n = 3, 4), in double: the order cut where
// a pivot of the Hankel matrix is at the bias' floor (as mboit_math.glsl), H c = (1, z0, ..),
// the support {z0, roots of sum c_i x^i}, its weights from sum_i w_i z_i^k = m_k, and the share
// beta w_0 + the weights in front of z0.
double transmittance_n(int n, double b0, const std::array<double, 8>& b, double z0, double bias = 5e-7,
                       double beta = 0.1) {
    if (b0 <= 1e-6) return 1.0;
    std::vector<double> m(2 * n + 1, 1.0);
    for (int k = 1; k <= 2 * n; ++k) m[k] = (1.0 - bias) * b[k - 1] / b0 + bias * (k % 2 ? 0.0 : 1.0 / (k + 1));
    const double floor_d[5] = {1.0, 1.0 / 3, 4.0 / 45, 4.0 / 175, 64.0 / 11025};
    int order = n;
    {  // the pivots of H without pivoting: D_jj of H = L D L^T
        std::vector<std::vector<double>> h(n + 1, std::vector<double>(n + 1));
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) h[i][j] = m[i + j];
        for (int j = 1; j <= n && order == n; ++j) {
            for (int r = j; r <= n; ++r) {
                const double f = h[r][j - 1] / h[j - 1][j - 1];
                for (int c = j - 1; c <= n; ++c) h[r][c] -= f * h[j - 1][c];
            }
            if (!(h[j][j] > bias * floor_d[j])) order = j - 1;
        }
    }
    std::vector<double> z = {z0};
    if (order > 0) {
        std::vector<std::vector<double>> h(order + 1, std::vector<double>(order + 1));
        std::vector<double> v(order + 1);
        for (int i = 0; i <= order; ++i) {
            v[i] = std::pow(z0, i);
            for (int j = 0; j <= order; ++j) h[i][j] = m[i + j];
        }
        for (double r : real_roots(solve(h, v))) z.push_back(r);
    }
    std::vector<std::vector<double>> vander(z.size(), std::vector<double>(z.size()));
    std::vector<double> rhs(z.size());
    for (size_t k = 0; k < z.size(); ++k) {
        rhs[k] = m[k];
        for (size_t i = 0; i < z.size(); ++i) vander[k][i] = std::pow(z[i], double(k));
    }
    const std::vector<double> w = solve(vander, rhs);
    double share = beta * w[0];
    for (size_t i = 1; i < z.size(); ++i) share += z[i] < z0 ? w[i] : 0.0;
    return std::clamp(std::exp(-b0 * share), 0.0, 1.0);
}

struct Fragment {
    glm::dvec4 c;
    double z, absorb;
};

// The pixel's fragments from the lists, alpha capped as mboit_common.glsl caps it, z warped as
// oit_blend.glsl warps it.
std::vector<Fragment> fragments(const Lists& l, int x, int y) {
    const double near = l.camera.near_plane, far = l.camera.far_plane;
    auto warp = [&](double d01) { return 2.0 * std::log((near + d01 * (far - near)) / near) / std::log(far / near) - 1.0; };
    std::vector<Fragment> frags;
    for (GLuint i = l.heads[size_t(y) * size_t(l.width) + size_t(x)]; i != 0xFFFFFFFFu; i = l.nodes.at(i).z) {
        glm::dvec4 c = node_color(l.nodes[i].x);
        c.a = std::min(c.a, 0.9999);
        frags.push_back({c, warp(node_depth(l.nodes[i])), -std::log(1.0 - c.a)});
    }
    return frags;
}

using cplx = std::complex<double>;

// The warped depth as an angle, mboit_common.glsl's mboit_phase (wrapping zone 0.1 pi).
const double kWrap = 0.1 * M_PI, kScale = M_PI - 0.5 * kWrap;
double phase(double z) { return (z + 1.0) * kScale; }

// Transmittance in front of z0 from n trigonometric moments t_k = sum A e^(i k phi) / b0, in
// double by other means than the shader: the order cut where a pivot of the Toeplitz matrix is
// at the bias' floor, T c = v(x0) by complex elimination, the roots of sum conj(c_j) x^j (on the
// unit circle) as the minima of |q| over 12,000 angles refined by Newton steps, their weights
// from sum_i w_i x_i^k = t_k, and the share as the shader counts it (1 in front, a ramp across
// the wrapping zone, beta at x0).
double transmittance_trig(int n, double b0, const std::vector<cplx>& tb, double z0, double bias, double beta = 0.1) {
    if (b0 <= 1e-6) return 1.0;
    std::vector<cplx> t(n + 1, 1.0);
    for (int k = 1; k <= n; ++k) t[k] = (1.0 - bias) * tb[k - 1] / b0;
    auto at = [&](int j, int k) { return j >= k ? t[j - k] : std::conj(t[k - j]); };
    int order = n;
    {  // pivots of T without pivoting
        std::vector<std::vector<cplx>> h(n + 1, std::vector<cplx>(n + 1));
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) h[i][j] = at(i, j);
        for (int j = 1; j <= n && order == n; ++j) {
            for (int r = j; r <= n; ++r) {
                const cplx f = h[r][j - 1] / h[j - 1][j - 1];
                for (int c = j - 1; c <= n; ++c) h[r][c] -= f * h[j - 1][c];
            }
            if (!(h[j][j].real() > bias)) order = j - 1;
        }
    }
    if (order == 0) return std::exp(-b0 * beta);
    const double phi0 = phase(z0);
    const cplx x0 = std::polar(1.0, phi0);
    std::vector<std::vector<cplx>> h(order + 1, std::vector<cplx>(order + 1));
    std::vector<cplx> v(order + 1);
    for (int i = 0; i <= order; ++i) {
        v[i] = std::pow(x0, i);
        for (int j = 0; j <= order; ++j) h[i][j] = at(i, j);
    }
    const std::vector<cplx> c = solve<cplx>(h, v);
    auto q = [&](cplx x) {
        cplx s = 0.0;
        for (int j = order; j >= 0; --j) s = s * x + std::conj(c[j]);
        return s;
    };
    auto dq = [&](cplx x) {
        cplx s = 0.0;
        for (int j = order; j >= 1; --j) s = s * x + double(j) * std::conj(c[j]);
        return s;
    };
    const int samples = 12000;
    std::vector<double> mag(samples);
    for (int i = 0; i < samples; ++i) mag[i] = std::abs(q(std::polar(1.0, 2.0 * M_PI * i / samples)));
    std::vector<std::pair<double, cplx>> minima;
    for (int i = 0; i < samples; ++i)
        if (mag[i] <= mag[(i + 1) % samples] && mag[i] < mag[(i + samples - 1) % samples])
            minima.push_back({mag[i], std::polar(1.0, 2.0 * M_PI * i / samples)});
    std::sort(minima.begin(), minima.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<cplx> x = {x0};
    for (int i = 0; i < order && i < int(minima.size()); ++i) {
        cplx r = minima[i].second;
        for (int it = 0; it < 20; ++it) r -= q(r) / dq(r);
        x.push_back(r);
    }
    std::vector<std::vector<cplx>> vander(x.size(), std::vector<cplx>(x.size()));
    std::vector<cplx> rhs(x.size());
    for (size_t k = 0; k < x.size(); ++k) {
        rhs[k] = at(int(k), 0);
        for (size_t i = 0; i < x.size(); ++i) vander[k][i] = std::pow(x[i], double(k));
    }
    const std::vector<cplx> w = solve<cplx>(vander, rhs);
    double share = beta * w[0].real();
    for (size_t i = 1; i < x.size(); ++i) {
        double ang = std::arg(x[i]);
        if (ang < 0.0) ang += 2.0 * M_PI;
        const double f = (ang < phi0 ? 1.0 : 0.0) + std::clamp((ang - 2.0 * kScale) / kWrap, 0.0, 1.0);
        share += f * w[i].real();
    }
    return std::clamp(std::exp(-b0 * share), 0.0, 1.0);
}

// A form of MBOIT: "power4", "power6", "power8", "trig2", "trig3", "trig4".
struct Form {
    std::string name;
    int n;      // the Hankel or Toeplitz order
    bool trig;
    double bias;
};
Form form(const std::string& name) {
    const bool trig = name.rfind("trig", 0) == 0;
    const int count = std::stoi(name.substr(trig ? 4 : 5));
    const double trig_bias[5] = {0, 0, 4e-7, 8e-7, 1.5e-6};
    return {name, trig ? count : count / 2, trig, trig ? trig_bias[count] : 5e-7};
}

// The pixel MBOIT of form `f` gives these fragments (power4: the paper's 4-moment algebra).
glm::dvec3 cpu_mboit(const std::vector<Fragment>& frags, const Form& form) {
    double b0 = 0.0;
    std::array<double, 8> b{};
    std::vector<cplx> tb(4, 0.0);
    for (const Fragment& f : frags) {
        b0 += f.absorb;
        for (int k = 0; k < 8; ++k) b[k] += f.absorb * std::pow(f.z, k + 1);
        for (int k = 0; k < 4; ++k) tb[k] += f.absorb * std::polar(1.0, (k + 1) * phase(f.z));
    }
    glm::dvec4 acc(0.0);
    for (const Fragment& f : frags) {
        const double t = form.trig      ? transmittance_trig(form.n, b0, tb, f.z, form.bias)
                         : form.n == 2 ? transmittance4(b0, {b[0], b[1], b[2], b[3]}, f.z, form.bias)
                                       : transmittance_n(form.n, b0, b, f.z, form.bias);
        acc += glm::dvec4(glm::dvec3(f.c) * f.c.a, f.c.a) * t;
    }
    const double t = std::exp(-b0);
    return glm::dvec3(acc) / acc.a * (1.0 - t) + t * glm::dvec3(1.0);
}

}  // namespace

class MboitForms : public ::testing::TestWithParam<std::string> {};  // power6, power8, trig2..trig4

TEST_P(MboitForms, EqualsACpuReferenceOfTheSameFragments) {
    const Form f = form(GetParam());
    Lists l = render_lists(kHere + "/graphs/mboit_and_lists.json", {"moments=" + f.name});
    size_t pixels = 0, layered = 0, off = 0;
    double worst = 0.0;
    for (int y = 0; y < l.height; ++y)
        for (int x = 0; x < l.width; ++x) {
            const std::vector<Fragment> frags = fragments(l, x, y);
            if (frags.empty()) continue;
            ++pixels;
            layered += frags.size() > 1;
            const glm::dvec3 want = cpu_mboit(frags, f);
            const int row = l.height - 1 - y;
            double d = 0.0;
            for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(double(l.mboit.at(x, row, k)) - want[k]));
            worst = std::max(worst, d);
            off += d > 3.0 / 255;
        }
    EXPECT_GT(pixels, 500u);
    EXPECT_GT(layered, 100u);
    std::printf("%s against the CPU's over %zu pixels (%zu layered): %zu over 3/255, largest %.2f/255\n",
                f.name.c_str(), pixels, layered, off, worst * 255);
    // float32 sums against double: where a pivot lies near the bias' floor the two may cut the
    // order differently; 2 % of the pixels at most.
    EXPECT_LE(off, pixels / 50) << "pixels more than 3/255 from the CPU's; largest " << worst * 255 << "/255";
}

TEST_P(MboitForms, OneFragmentIsExactAndFewLayersAreNearTheExactResolve) {
    // One fragment alone: the pixel is that fragment's colour over the background, exactly (the
    // white-pixel bug of an earlier 6/8-moment attempt). Two or three layers: as near the exact
    // resolve as 4 moments are, or nearer.
    const Form f = form(GetParam());
    Lists l = render_lists(kHere + "/graphs/mboit_and_lists.json", {"moments=" + f.name});
    Lists four = render_lists(kHere + "/graphs/mboit_and_lists.json", {});
    size_t single = 0, few = 0;
    double err = 0.0, err4 = 0.0;
    for (int y = 0; y < l.height; ++y)
        for (int x = 0; x < l.width; ++x) {
            const size_t count = fragments(l, x, y).size();
            if (count == 0) continue;
            const int row = l.height - 1 - y;
            if (count == 1) {
                ++single;
                for (int k = 0; k < 3; ++k)
                    ASSERT_NEAR(l.mboit.at(x, row, k), l.exact.at(x, row, k), 2.0 / 255) << "pixel " << x << "," << row;
            } else if (count <= 3) {
                ++few;
                for (int k = 0; k < 3; ++k) {
                    err += std::abs(double(l.mboit.at(x, row, k)) - l.exact.at(x, row, k));
                    err4 += std::abs(double(four.mboit.at(x, row, k)) - four.exact.at(x, row, k));
                }
            }
        }
    EXPECT_GT(single, 100u);
    ASSERT_GT(few, 50u);
    std::printf("%s, pixels of 2-3 layers: mean error %.2f/255 (4 power moments: %.2f/255)\n", f.name.c_str(),
                err / (3.0 * few) * 255, err4 / (3.0 * few) * 255);
    EXPECT_LT(err, err4) << "these moments must resolve a few layers better than 4 power moments";
    EXPECT_LT(err / (3.0 * few), 4.0 / 255);
}

// Lines along x through the middle row at the given warped depths (-1: the near plane, 1: the
// far plane; a depth twice: two lines at identical depth), for a camera 170 from the centre of
// a 200-cube that two short lines mark: inside its bounding sphere, so camera.cpp puts the near
// plane at 1 % of the radius and warped depths span all of [-1, 1].
struct DeepScene {
    Scene scene;
    std::string camera_path;
};
DeepScene deep_lines_scene(const std::vector<double>& warped) {
    std::vector<StraightLine> lines(2);
    lines[0].from = {-100.0f, -100.0f, -100.0f}, lines[0].to = {-99.0f, -100.0f, -100.0f};
    lines[1].from = {99.0f, 100.0f, 100.0f}, lines[1].to = {100.0f, 100.0f, 100.0f};
    DeepScene d;
    d.camera_path = write_camera_down_z(test_scratch_dir("pathlet_mboit") + "/deep_cam.json", {0, 0, 0}, 170, 40);
    const Camera c = CameraPath::load(d.camera_path).at(6.0, straight_lines_scene(lines).bounds(), kSmall);
    for (size_t i = 0; i < warped.size(); ++i) {
        const double dist = c.near_plane * std::pow(double(c.far_plane) / c.near_plane, 0.5 * (warped[i] + 1.0));
        const float z = float(170.0 - dist);
        lines.push_back({.from = {-30.0f, 0.0f, z}, .to = {30.0f, 0.0f, z}, .speed = 1.0f + 0.1f * float(i), .arrays = {}});
    }
    d.scene = straight_lines_scene(lines);
    return d;
}

// Each pixel of `l` with at least `min_layers` fragments against the CPU reference of form `f`:
// how many, how many more than 3/255 off, the largest difference.
struct Against {
    size_t pixels = 0, off = 0;
    double worst = 0.0;
};
Against against_cpu(const Lists& l, const Form& f, size_t min_layers) {
    Against a;
    for (int y = 0; y < l.height; ++y)
        for (int x = 0; x < l.width; ++x) {
            const std::vector<Fragment> frags = fragments(l, x, y);
            if (frags.size() < min_layers) continue;
            ++a.pixels;
            const glm::dvec3 want = cpu_mboit(frags, f);
            double d = 0.0;
            for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(double(l.mboit.at(x, l.height - 1 - y, k)) - want[k]));
            a.worst = std::max(a.worst, d);
            a.off += d > 3.0 / 255;
        }
    return a;
}

class MboitTrig : public ::testing::TestWithParam<std::string> {};  // trig2..trig4

TEST_P(MboitTrig, LayersFromTheNearPlaneOnMatchTheReferenceAcrossTheWrappingZone) {
    // Thirteen lines through the middle row, from just behind the near plane (warped depth
    // -0.984, angle 0.05) to 0.90: more depths than moments, so the kernel's roots fall between
    // the layers, and the nearest layer's root, reconstructed in float32, can land a little
    // below angle 0, i.e. in the wrapping zone just under 2 pi. The ramp counts it as in front
    // of the other layers, as the CPU reference in double does; without it the nearest layer
    // stops occluding (removing the ramp: trig2 28, trig4 120 of 168 pixels over 3/255; trig3's
    // roots stay out of the zone here).
    const Form f = form(GetParam());
    std::vector<double> warped;
    for (int i = 0; i < 13; ++i) warped.push_back(-0.984 + 0.157 * i);
    const DeepScene d = deep_lines_scene(warped);
    Lists l = render_lists(kHere + "/graphs/mboit_and_lists.json", {"moments=" + f.name, "window=0"}, d.scene,
                           d.camera_path);
    const Against a = against_cpu(l, f, 10);
    std::printf("%s, pixels of 10-13 layers from the near plane on: %zu, %zu over 3/255 from the CPU's, largest "
                "%.2f/255\n", f.name.c_str(), a.pixels, a.off, a.worst * 255);
    EXPECT_GT(a.pixels, 100u);
    // Where the nearest layer's root sits near angle 0 the float32 and double reconstructions
    // differ by a little more than elsewhere (2, 0, 8 pixels of 168 when written): 10 % at most.
    EXPECT_LE(a.off, a.pixels / 10) << "largest " << a.worst * 255 << "/255";
}

class MboitCut : public ::testing::TestWithParam<std::string> {};  // power6, power8

TEST_P(MboitCut, TwoDepthsCutTheOrderAtThePivotsFloor) {
    // Five lines at two depths (two, then three at identical depth) in every pixel of the middle
    // row: the Hankel matrix is singular up to the bias beyond order 1, its later pivots float32
    // rounding noise. The cut at the pivots' floor keeps the reconstruction on the two depths,
    // as the CPU reference in double; without it the noise pivots make the support garbage
    // (removing the cut: power6 88 and 43, power8 90 and 32 pixels over 3/255, up to 90/255).
    const Form f = form(GetParam());
    const std::vector<double> scenes[] = {{-0.8, -0.8, 0.7, 0.7, 0.7}, {-0.6, -0.6, 0.75, 0.75, 0.75}};
    for (const auto& depths : scenes) {
        const DeepScene d = deep_lines_scene(depths);
        Lists l = render_lists(kHere + "/graphs/mboit_and_lists.json", {"moments=" + f.name, "window=0"}, d.scene,
                               d.camera_path);
        const Against a = against_cpu(l, f, depths.size());
        std::printf("%s, 5 lines at warped depths %.2f and %.2f: %zu pixels, %zu over 3/255 from the CPU's, largest "
                    "%.2f/255\n", f.name.c_str(), depths.front(), depths.back(), a.pixels, a.off, a.worst * 255);
        EXPECT_GT(a.pixels, 100u);
        EXPECT_EQ(a.off, 0u) << "largest " << a.worst * 255 << "/255";
    }
}

INSTANTIATE_TEST_SUITE_P(Moments, MboitCut, ::testing::Values("power6", "power8"),
                         [](const auto& info) { return info.param; });

INSTANTIATE_TEST_SUITE_P(Moments, MboitTrig, ::testing::Values("trig2", "trig3", "trig4"),
                         [](const auto& info) { return info.param; });
INSTANTIATE_TEST_SUITE_P(Moments, MboitForms, ::testing::Values("power6", "power8", "trig2", "trig3", "trig4"),
                         [](const auto& info) { return info.param; });

TEST(Mboit, MoreMomentsAreNearerTheExactReferenceOnThePhantom) {
    // The small phantom, every line whole, against variant2_exact: RMSE over the pixels either
    // covers falls from 4 to 6 to 8 moments (0.0129, 0.0118, 0.0104 when written).
    auto render_graph = [](const std::string& graph, std::vector<std::string> sets) {
        RenderOptions opt;
        opt.graph_path = kSrc + "/graphs/" + graph + ".json";
        sets.insert(sets.end(), {"window=0", "overlay=false", "wall=false"});
        opt.sets = sets;
        opt.size = {320, 180};
        opt.time.start = 2.0;
        return render_frame(test_runtime(), small_phantom_scene(), opt, {"final"})["final"];
    };
    const Image exact = render_graph("variant2_exact", {});
    const Image forms[3] = {render_graph("variant2_mboit", {}), render_graph("variant2_mboit8", {"moments=power6"}),
                            render_graph("variant2_mboit8", {})};
    double rmse[3];
    for (int f = 0; f < 3; ++f) {
        double sum = 0.0;
        size_t covered = 0;
        for (int y = 0; y < exact.height; ++y)
            for (int x = 0; x < exact.width; ++x) {
                bool any = false;
                double d2 = 0.0;
                for (int k = 0; k < 3; ++k) {
                    any = any || exact.at(x, y, k) < 1.0f || forms[f].at(x, y, k) < 1.0f;
                    d2 += std::pow(double(forms[f].at(x, y, k)) - exact.at(x, y, k), 2);
                }
                if (!any) continue;
                ++covered;
                sum += d2 / 3.0;
            }
        ASSERT_GT(covered, 2000u);
        rmse[f] = std::sqrt(sum / double(covered));
    }
    std::printf("small phantom, every line, RMSE against variant2_exact: power4 %.4f, power6 %.4f, power8 %.4f\n",
                rmse[0], rmse[1], rmse[2]);
    EXPECT_LT(rmse[1], 0.97 * rmse[0]);
    EXPECT_LT(rmse[2], 0.97 * rmse[1]);
}

TEST(Mboit, LoneLinesAtEveryDepthKeepTheirColour) {
    // Lines side by side, each alone in its pixels, from the near to the far end of the depth
    // range (warped z from -1 to 1): each form gives the exact picture there. With 4 moments the
    // paper's expectation through monomials dropped such lines in dashes on the CFD aorta; a
    // pivot at the bias' floor turned into noise gives garbage support points.
    std::vector<StraightLine> lines;
    for (int i = 0; i < 13; ++i)
        lines.push_back({.from = {0.0f, 1.5f * float(i), -24.0f + 4.0f * float(i)},
                         .to = {10.0f, 1.5f * float(i), -24.0f + 4.0f * float(i)}, .speed = 1.0f + 0.2f * float(i)});
    const Scene scene = straight_lines_scene(lines);
    const std::string cam = write_camera_down_z(test_scratch_dir("pathlet_mboit") + "/cam.json", {5, 9, 0}, 60, 30);
    auto render_graph = [&](const std::string& graph, std::vector<std::string> sets) {
        RenderOptions opt;
        opt.graph_path = kSrc + "/graphs/" + graph + ".json";
        sets.insert(sets.end(), {"window=0", "overlay=false", "wall=false", "lod=0", "color_hook=uniform_fade.glsl",
                                 "tail_fade=0", "head_fade=0", "line_width=0.8", "speed_min=1", "speed_max=3.4"});
        opt.sets = sets;
        opt.size = {320, 180};
        opt.time.start = 5.0;
        opt.camera_path = cam;
        return render_frame(test_runtime(), scene, opt, {"final"})["final"];
    };
    const Image exact = render_graph("variant2_exact", {});
    const std::pair<std::string, std::string> forms[] = {
        {"variant2_mboit", ""},           {"variant2_mboit8", "moments=power6"}, {"variant2_mboit8", "moments=power8"},
        {"variant2_mboit", "moments=trig2"}, {"variant2_mboit8", "moments=trig3"}, {"variant2_mboit8", "moments=trig4"}};
    for (const auto& [graph, set] : forms) {
        const Image im = render_graph(graph, set.empty() ? std::vector<std::string>{} : std::vector<std::string>{set});
        size_t covered = 0, off = 0;
        double worst = 0.0;
        for (int y = 0; y < exact.height; ++y)
            for (int x = 0; x < exact.width; ++x) {
                double d = 0.0;
                bool any = false;
                for (int k = 0; k < 3; ++k) {
                    any = any || exact.at(x, y, k) < 1.0f;
                    d = std::max(d, std::abs(double(im.at(x, y, k)) - exact.at(x, y, k)));
                }
                covered += any;
                off += d > 2.0 / 255;
                worst = std::max(worst, d);
            }
        EXPECT_GT(covered, 1500u);
        EXPECT_EQ(off, 0u) << graph << " " << set << ": pixels more than 2/255 from the exact picture (largest "
                           << worst * 255 << "/255)";
    }
}

TEST(Mboit, HighMomentsNeedTheirTarget) {
    // variant2_mboit keeps 4 moments: power8 there fails at setup naming the pin and the graph
    // that has it.
    RenderOptions opt;
    opt.graph_path = kSrc + "/graphs/variant2_mboit.json";
    opt.sets = {"moments=power8"};
    opt.size = kSmall;
    opt.time.start = 6.0;
    try {
        render_frame(test_runtime(), helix_bundle_scene(), opt, {"final"});
        FAIL() << "power8 without moments_high rendered";
    } catch (const std::exception& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("moments_high"), std::string::npos) << what;
        EXPECT_NE(what.find("variant2_mboit8"), std::string::npos) << what;
    }
}

TEST(Mboit, EqualsACpuMboitOfTheSameFragments) {
    Lists l = render_lists(kHere + "/graphs/mboit_and_lists.json", {});
    const double near = l.camera.near_plane, far = l.camera.far_plane;
    auto warp = [&](double d01) { return 2.0 * std::log((near + d01 * (far - near)) / near) / std::log(far / near) - 1.0; };
    size_t pixels = 0, layered = 0, off = 0;
    double worst = 0.0;
    for (int y = 0; y < l.height; ++y)
        for (int x = 0; x < l.width; ++x) {
            struct F { glm::dvec4 c; double z, absorb; };
            std::vector<F> frags;
            for (GLuint i = l.heads[size_t(y) * size_t(l.width) + size_t(x)]; i != 0xFFFFFFFFu; i = l.nodes.at(i).z) {
                glm::dvec4 c = node_color(l.nodes[i].x);
                c.a = std::min(c.a, 0.9999);
                frags.push_back({c, warp(node_depth(l.nodes[i])), -std::log(1.0 - c.a)});
            }
            if (frags.empty()) continue;
            ++pixels;
            layered += frags.size() > 1;
            double b0 = 0.0;
            std::array<double, 4> b{};
            for (const F& f : frags) {
                b0 += f.absorb;
                for (int k = 0; k < 4; ++k) b[k] += f.absorb * std::pow(f.z, k + 1);
            }
            glm::dvec4 acc(0.0);
            for (const F& f : frags) acc += glm::dvec4(glm::dvec3(f.c) * f.c.a, f.c.a) * transmittance4(b0, b, f.z);
            const double t = std::exp(-b0);
            const glm::dvec3 want = glm::dvec3(acc) / acc.a * (1.0 - t) + t * glm::dvec3(1.0);
            const int row = l.height - 1 - y;
            double d = 0.0;
            for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(double(l.mboit.at(x, row, k)) - want[k]));
            worst = std::max(worst, d);
            off += d > 3.0 / 255;
            ASSERT_EQ(l.mboit.at(x, row, 3), 1.0f) << "alpha 1 where a fragment landed";
        }
    EXPECT_GT(pixels, 500u);
    EXPECT_GT(layered, 100u) << "the scene must have overlapping fragments to test the blend";
    // float32 moments against double: a pixel whose reconstruction is ill-conditioned (nearly
    // coincident layers) may differ; 1 % of them at most.
    EXPECT_LE(off, pixels / 100) << "pixels more than 3/255 from the CPU's MBOIT; largest " << worst * 255 << "/255";
    std::printf("MBOIT against the CPU's over %zu pixels (%zu layered): %zu over 3/255, largest %.2f/255\n", pixels,
                layered, off, worst * 255);
}

TEST(Mboit, OneFragmentIsExactAndLayersAreCloserThanWithoutOrder) {
    // One fragment: MBOIT is exact. Layered pixels: nearer the exact resolve than a blurred
    // reconstruction from the same sums (moments half replaced by the uniform distribution's,
    // moment_bias 0.5, and no overestimation).
    Lists l = render_lists(kHere + "/graphs/mboit_and_lists.json", {});
    Lists blind = render_lists(kHere + "/graphs/mboit_and_lists.json", {"accum.moment_bias=0.5", "accum.overestimation=0"});
    double err = 0.0, err_blind = 0.0;
    size_t single = 0, layered = 0;
    for (int y = 0; y < l.height; ++y)
        for (int x = 0; x < l.width; ++x) {
            const GLuint head = l.heads[size_t(y) * size_t(l.width) + size_t(x)];
            if (head == 0xFFFFFFFFu) continue;
            const int row = l.height - 1 - y;
            if (l.nodes.at(head).z == 0xFFFFFFFFu) {
                ++single;
                for (int k = 0; k < 3; ++k)
                    ASSERT_NEAR(l.mboit.at(x, row, k), l.exact.at(x, row, k), 2.0 / 255) << "pixel " << x << "," << row;
                continue;
            }
            ++layered;
            for (int k = 0; k < 3; ++k) {
                err += std::abs(double(l.mboit.at(x, row, k)) - l.exact.at(x, row, k));
                err_blind += std::abs(double(blind.mboit.at(x, row, k)) - blind.exact.at(x, row, k));
            }
        }
    EXPECT_GT(single, 100u);
    ASSERT_GT(layered, 100u);
    std::printf("mean error of layered pixels against the exact resolve: MBOIT %.2f/255, blurred %.2f/255\n",
                err / (3.0 * layered) * 255, err_blind / (3.0 * layered) * 255);
    EXPECT_LT(err, 0.8 * err_blind) << "the moments must carry the depth order";
}

TEST(Mboit, Variant2MboitGolden) {
    RenderOptions opt;
    opt.graph_path = kSrc + "/graphs/variant2_mboit.json";
    opt.sets = {"line_width=1.2", "window=3", "overlay=false"};
    opt.size = kSmall;
    opt.time.start = 6.0;
    Frame f = render_frame(test_runtime(), helix_bundle_scene(), opt, {"final"});
    EXPECT_FALSE(has_nan(f["final"]));
    EXPECT_TRUE(matches_golden(f["final"], kHere + "/goldens/variant2_mboit.png"));
}
