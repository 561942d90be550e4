// Weighted blended OIT (wboit_accum -> oit_composite) on real GL (llvmpipe): the picture against
// a CPU WBOIT of the very fragments fill_list stores for the same lines, single-layer pixels
// against the exact resolve, and a golden of graphs/variant2_wboit.json.
#include "executor.hpp"
#include "frame_capture.hpp"
#include "golden.hpp"
#include "oit_lists.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

using namespace pathlet;

namespace {

const std::string kSrc = PATHLET_SOURCE_DIR;
const std::string kHere = PATHLET_TEST_SOURCE_DIR;
const glm::ivec2 kSmall{160, 120};

struct Lists : OitLists {
    Image exact, wboit;         // top-down
};

Lists render_lists(std::vector<std::string> sets) {
    RenderOptions opt;
    opt.graph_path = kHere + "/graphs/wboit_and_lists.json";
    opt.sets = std::move(sets);
    opt.size = kSmall;
    opt.time.start = opt.time.end = 6.0;
    opt.warmup = 0;
    opt.write_images = false;
    opt.quiet = true;
    Lists l;
    render(test_runtime(), helix_bundle_scene(), opt, [&](const Executor& ex, size_t) {
        static_cast<OitLists&>(l) = read_oit_lists(ex);
        l.exact = read_resource(ex.texture("exact"));
        l.wboit = read_resource(ex.texture("wboit"));
    });
    return l;
}


// wboit_accum's default weight, exponential with falloff 25 (and the paper's eq. 10, depth_cubed).
double weight(double a, double d) { return a * std::max(1e-4, 3e3 * std::exp(-25.0 * d)); }
double weight_eq10(double a, double d) { return a * std::max(1e-2, 3e3 * std::pow(1.0 - d, 3.0)); }

}  // namespace

TEST(Wboit, EqualsACpuWboitOfTheSameFragments) {
  for (const bool eq10 : {false, true}) {
    SCOPED_TRACE(eq10 ? "depth_cubed" : "exponential");
    Lists l = render_lists(eq10 ? std::vector<std::string>{"accum.weight=depth_cubed"} : std::vector<std::string>{});
    size_t pixels = 0, layered = 0;
    double worst = 0.0;
    for (int y = 0; y < l.height; ++y)
        for (int x = 0; x < l.width; ++x) {
            glm::dvec4 acc(0.0);
            double revealage = 1.0;
            int n = 0;
            for (GLuint i = l.heads[size_t(y) * size_t(l.width) + size_t(x)]; i != 0xFFFFFFFFu; i = l.nodes.at(i).z) {
                const glm::dvec4 c = node_color(l.nodes[i].x);
                const double w = eq10 ? weight_eq10(c.a, node_depth(l.nodes[i])) : weight(c.a, node_depth(l.nodes[i]));
                acc += glm::dvec4(glm::dvec3(c) * c.a, c.a) * w;
                revealage *= 1.0 - c.a;
                ++n;
            }
            if (n == 0) continue;
            ++pixels;
            layered += n > 1;
            const glm::dvec3 want = glm::dvec3(acc) / acc.a * (1.0 - revealage) + revealage * glm::dvec3(1.0);
            const int row = l.height - 1 - y;
            for (int k = 0; k < 3; ++k) {
                worst = std::max(worst, std::abs(double(l.wboit.at(x, row, k)) - want[k]));
                ASSERT_NEAR(l.wboit.at(x, row, k), want[k], 3.0 / 255) << "pixel " << x << "," << row << " channel " << k
                                                                        << ", " << n << " fragments";
            }
            ASSERT_EQ(l.wboit.at(x, row, 3), 1.0f) << "alpha 1 where a fragment landed";
        }
    EXPECT_GT(pixels, 500u);
    EXPECT_GT(layered, 100u) << "the scene must have overlapping fragments to test the blend";
    std::printf("WBOIT (%s) against the CPU's over %zu pixels (%zu layered): largest difference %.2f/255\n",
                eq10 ? "depth_cubed" : "exponential", pixels, layered, worst * 255);
  }
}

TEST(Wboit, OneFragmentIsExactAndEmptyPixelsAreBackground) {
    Lists l = render_lists({});
    size_t single = 0, empty = 0;
    for (int y = 0; y < l.height; ++y)
        for (int x = 0; x < l.width; ++x) {
            const GLuint head = l.heads[size_t(y) * size_t(l.width) + size_t(x)];
            const int row = l.height - 1 - y;
            if (head == 0xFFFFFFFFu) {
                ++empty;
                for (int k = 0; k < 3; ++k) ASSERT_EQ(l.wboit.at(x, row, k), 1.0f) << "white background";
                ASSERT_EQ(l.wboit.at(x, row, 3), 0.0f);
                continue;
            }
            if (l.nodes.at(head).z != 0xFFFFFFFFu) continue;
            ++single;
            for (int k = 0; k < 3; ++k)
                ASSERT_NEAR(l.wboit.at(x, row, k), l.exact.at(x, row, k), 2.0 / 255) << "pixel " << x << "," << row;
        }
    EXPECT_GT(single, 100u);
    EXPECT_GT(empty, 1000u);
}

TEST(Wboit, Variant2WboitGolden) {
    RenderOptions opt;
    opt.graph_path = kSrc + "/graphs/variant2_wboit.json";
    opt.sets = {"line_width=1.2", "window=3", "overlay=false"};
    opt.size = kSmall;
    opt.time.start = 6.0;
    Frame f = render_frame(test_runtime(), helix_bundle_scene(), opt, {"final"});
    EXPECT_FALSE(has_nan(f["final"]));
    EXPECT_TRUE(matches_golden(f["final"], kHere + "/goldens/variant2_wboit.png"));
}
