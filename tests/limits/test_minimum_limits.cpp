// Every shipped graph on a minimal GL 4.5 driver: under PATHLET_GL_LIMITS=minimum the engine acts
// as if every binding and resource limit were the spec's minimum (8 image units, no storage blocks
// in geometry shaders, 8 combined output resources, ...) and checks every linked program against
// them, so a graph that renders here renders on any conforming driver. It must render, and
// render the same picture: the limits change where things are bound, never what is drawn.
#include "frame_capture.hpp"
#include "shipped_graphs.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include <cstdlib>

using namespace pathlet;

namespace {

struct MinimumLimits {
    MinimumLimits() { ::setenv("PATHLET_GL_LIMITS", "minimum", 1); }
    ~MinimumLimits() { ::unsetenv("PATHLET_GL_LIMITS"); }
};

// Every texture output the graph captures or keeps: identical bytes under both limits.
void expect_same_under_minimum(const ShippedGraph& g) {
    SCOPED_TRACE(g.name);
    test_runtime();  // the GL context unsupported_here asks
    if (const std::string why = g.unsupported_here(); !why.empty()) {
        std::printf("skipped: %s\n", why.c_str());
        return;
    }
    RenderOptions opt;
    opt.graph_path = g.path;
    opt.size = {160, 90};
    opt.time.start = 2.0;  // the middle of the small phantom's 0..4 s
    std::vector<std::string> outputs;
    for (const auto& o : g.file.outputs) outputs.push_back(o.resource);
    ASSERT_FALSE(outputs.empty());
    const Frame normal = render_frame(test_runtime(), small_phantom_scene(), opt, outputs);
    Frame minimum;
    {
        MinimumLimits m;
        try {
            minimum = render_frame(test_runtime(), small_phantom_scene(), opt, outputs);
        } catch (const std::exception& e) {
            ADD_FAILURE() << g.name << " does not run on a minimal GL 4.5 driver: " << e.what();
            return;
        }
    }
    for (const std::string& name : outputs) {
        const Image &a = normal[name], &b = minimum[name];
        ASSERT_EQ(a.pixels.size(), b.pixels.size()) << name;
        size_t differ = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] != b.pixels[i];
        EXPECT_EQ(differ, 0u) << g.name << " '" << name << "': " << differ << " values differ under the minimum limits";
    }
}

}  // namespace

TEST(MinimumLimits, EveryShippedGraphRendersTheSamePictureOnAMinimalGl45Driver) {
    for (const ShippedGraph& g : shipped_graphs()) expect_same_under_minimum(g);
}
