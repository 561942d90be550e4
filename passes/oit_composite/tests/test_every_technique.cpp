// One fade hook through every transparency technique: every shipped
// variant2_* graph has the variable color_hook, and `--set color_hook=FILE` (here through
// Runtime::user_sets, as the command line does it) puts the same GLSL file into each. A hook
// that paints every line blue (no colour map of the default graphs makes blue) must turn each
// technique's picture blue where lines are, and the end fade's parameters it does not declare
// are dropped, not refused. Graphs the driver cannot run (MLAB without fragment shader
// interlock) are skipped, saying so.
#include "frame_capture.hpp"
#include "shipped_graphs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

using namespace pathlet;

namespace {

// Shares of the covered (non-white) pixels that are blue-dominated, and how many are covered.
struct Blue {
    double share = 0.0;
    size_t covered = 0;
};
Blue blue_share(const Image& im) {
    Blue b;
    size_t blue = 0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            const float r = im.at(x, y, 0), g = im.at(x, y, 1), bl = im.at(x, y, 2);
            if (r + g + bl > 2.9f) continue;
            ++b.covered;
            blue += bl > r + 0.15f && bl > g + 0.15f;
        }
    b.share = b.covered ? double(blue) / double(b.covered) : 0.0;
    return b;
}

// The helix bundle as every test here draws it: 160x120 at t = 6 s, a 3 s window, thick lines,
// no overlay or wall.
RenderOptions helix_options(const std::string& graph_path) {
    RenderOptions opt;
    opt.graph_path = graph_path;
    opt.size = {160, 120};
    opt.time.start = 6.0;
    opt.sets = {"line_width=1.2", "window=3", "overlay=false", "wall=false"};
    return opt;
}

}  // namespace

TEST(EveryTechnique, OneFadeHookGoesIntoEveryVariant2Graph) {
    const std::string hook = test_scratch_dir("pathlet_every_technique") + "/blue_fade.glsl";
    std::ofstream(hook) << "// every line blue, half as opaque past the middle of its pathlet\n"
                           "vec4 line_color_hook(vec4 rgba, LinePoint p) {\n"
                           "    return vec4(0.1, 0.2, 1.0, rgba.a * (p.age < 0.5 ? 1.0 : 0.5));\n"
                           "}\n";
    Runtime& rt = test_runtime();
    size_t graphs = 0;
    for (const ShippedGraph& g : shipped_graphs()) {
        if (g.name.rfind("variant2_", 0) != 0) continue;
        SCOPED_TRACE(g.name);
        ASSERT_TRUE(g.has_variable("color_hook")) << g.name << " has no variable color_hook";
        if (const std::string why = g.unsupported_here(); !why.empty()) {
            std::printf("skipped: %s\n", why.c_str());
            continue;
        }
        RenderOptions opt = helix_options(g.path);
        const Frame plain = render_frame(rt, helix_bundle_scene(), opt, {"final"});
        opt.sets.push_back("color_hook=" + hook);
        opt.sets = rt.user_sets(opt.sets);
        const Frame hooked = render_frame(rt, helix_bundle_scene(), opt, {"final"});
        const Blue before = blue_share(plain["final"]), after = blue_share(hooked["final"]);
        std::printf("%-24s blue share of covered pixels: %.3f without the hook, %.3f with it (%zu covered)\n",
                    g.name.c_str(), before.share, after.share, after.covered);
        EXPECT_GT(after.covered, 500u) << "the hooked picture shows lines";
        EXPECT_LT(before.share, 0.02) << "the default colour map is not blue";
        EXPECT_GT(after.share, 0.85) << "the hook's blue in " << g.name;
        ++graphs;
    }
    EXPECT_GE(graphs, 7u) << "variant2_oit, _ao, _vao, wboit, wboit_ao, mboit, mboit_ao at least";
}

TEST(EveryTechnique, TheOpaqueCoresAoCombinesWithEachBlendTechnique) {
    // variant2_*_ao applies the core's LineAO per fragment inside the accumulation: with strength
    // 0 (AO 1 everywhere) the picture is the plain technique's, with strength 2 it is darker.
    Runtime& rt = test_runtime();
    auto mean_luma = [](const Image& im, size_t& covered) {
        double sum = 0.0;
        covered = 0;
        for (int y = 0; y < im.height; ++y)
            for (int x = 0; x < im.width; ++x) {
                const float r = im.at(x, y, 0), g = im.at(x, y, 1), b = im.at(x, y, 2);
                if (r + g + b > 2.9f) continue;
                ++covered;
                sum += 0.2126 * r + 0.7152 * g + 0.0722 * b;
            }
        return covered ? sum / double(covered) : 0.0;
    };
    for (const char* technique : {"variant2_wboit", "variant2_mboit"}) {
        SCOPED_TRACE(technique);
        RenderOptions opt = helix_options(shipped_graph(technique).path);
        const Frame plain = render_frame(rt, helix_bundle_scene(), opt, {"final"});
        opt.graph_path = shipped_graph(std::string(technique) + "_ao").path;
        opt.sets.push_back("strength=0");
        const Frame unlit = render_frame(rt, helix_bundle_scene(), opt, {"final"});
        opt.sets.back() = "strength=2";
        const Frame lit = render_frame(rt, helix_bundle_scene(), opt, {"final"});
        size_t n = 0, differ = 0;
        for (size_t i = 0; i < plain["final"].pixels.size(); ++i)
            differ += std::abs(plain["final"].pixels[i] - unlit["final"].pixels[i]) > 1.5f / 255;
        EXPECT_EQ(differ, 0u) << "AO 1 must leave the technique's picture as it is";
        size_t n_lit = 0;
        const double before = mean_luma(unlit["final"], n), after = mean_luma(lit["final"], n_lit);
        std::printf("%s_ao: mean luminance of covered pixels %.4f with AO strength 0, %.4f with 2\n", technique, before,
                    after);
        EXPECT_GT(n, 500u);
        EXPECT_LT(after, before - 0.01) << "the core's AO darkens";
    }
}

TEST(EveryTechnique, TheHookDecidesTheOpaqueCoreToo) {
    // fade_core keeps where the graph's colour hook reaches core_alpha (0.5): with a hook that
    // makes every line 0.3 opaque there is no core, so LineAO has nothing to darken and AO
    // strength 2 leaves each _ao picture as strength 0 does. (With the end fade as the core,
    // whatever the hook, the middles of the pathlets were core and darkened.)
    const std::string hook = test_scratch_dir("pathlet_every_technique") + "/faint_fade.glsl";
    std::ofstream(hook) << "vec4 line_color_hook(vec4 rgba, LinePoint p) { return vec4(rgba.rgb, 0.3 * rgba.a); }\n";
    Runtime& rt = test_runtime();
    size_t graphs = 0;
    for (const ShippedGraph& g : shipped_graphs()) {
        const std::string& n = g.name;
        if (n.rfind("variant2_", 0) != 0 || n.size() < 3 || n.compare(n.size() - 3, 3, "_ao") != 0) continue;
        SCOPED_TRACE(n);
        if (const std::string why = g.unsupported_here(); !why.empty()) {
            std::printf("skipped: %s\n", why.c_str());
            continue;
        }
        RenderOptions opt = helix_options(g.path);
        opt.sets.push_back("color_hook=" + hook);
        opt.sets.push_back("strength=0");
        opt.sets = rt.user_sets(opt.sets);
        const Frame unlit = render_frame(rt, helix_bundle_scene(), opt, {"final"});
        opt.sets.back() = "strength=2";
        const Frame lit = render_frame(rt, helix_bundle_scene(), opt, {"final"});
        size_t differ = 0, covered = 0;
        const Image& a = unlit["final"];
        for (size_t i = 0; i < a.pixels.size(); ++i) differ += std::abs(a.pixels[i] - lit["final"].pixels[i]) > 1.5f / 255;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x) covered += a.at(x, y, 0) + a.at(x, y, 1) + a.at(x, y, 2) < 2.9f;
        std::printf("%-24s faint hook: %zu of %zu values differ between AO strength 0 and 2 (%zu covered pixels)\n",
                    n.c_str(), differ, a.pixels.size(), covered);
        EXPECT_GT(covered, 500u) << "the faint lines are drawn";
        EXPECT_EQ(differ, 0u) << "a core the hook does not make opaque must not exist";
        ++graphs;
    }
    EXPECT_GE(graphs, 3u) << "variant2_oit_ao, wboit_ao, mboit_ao at least";
}
