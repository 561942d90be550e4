// Moment-based OIT (mboit_moments -> mboit_accum -> oit_composite) on real GL (llvmpipe): the
// picture against a CPU MBOIT in double precision of the very fragments fill_list stores for
// the same lines (a 3x3 solve with pivoting and Lagrange weights, not the shader's L D L^T and
// Newton form), single-layer pixels against the exact resolve, layered ones nearer it than an
// order-blind blend of the same sums, and a golden of graphs/variant2_mboit.json.
#include "camera.hpp"
#include "executor.hpp"
#include "frame_capture.hpp"
#include "golden.hpp"
#include "oit_lists.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
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

Lists render_lists(const std::string& graph, std::vector<std::string> sets) {
    RenderOptions opt;
    opt.graph_path = graph;
    opt.sets = std::move(sets);
    opt.size = kSmall;
    opt.time.start = opt.time.end = 6.0;
    opt.warmup = 0;
    opt.write_images = false;
    opt.quiet = true;
    Lists l;
    l.camera = frame_bounds(helix_bundle_scene().bounds(), opt.size);
    render(test_runtime(), helix_bundle_scene(), opt, [&](const Executor& ex, size_t) {
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

}  // namespace

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
