// graphs/variant4_opacity.json as a whole: its golden, the same picture under the GL 4.5
// minimum limits (PATHLET_GL_LIMITS=minimum), and the line kit refusing a hook that reads
// hook_buffer when the pass has none connected.
#include "frame_capture.hpp"
#include "golden.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

using namespace pathlet;

namespace {

const std::string kSrc = PATHLET_SOURCE_DIR;
const std::string kHere = PATHLET_TEST_SOURCE_DIR;
const std::string kGraph = kSrc + "/graphs/variant4_opacity.json";

Frame render(const std::string& graph, std::vector<std::string> sets, const Scene& scene, glm::ivec2 size, double t) {
    RenderOptions opt;
    opt.graph_path = graph;
    opt.sets = std::move(sets);
    opt.size = size;
    opt.time.start = t;
    return render_frame(test_runtime(), scene, opt, {"final"});
}

}  // namespace

TEST(Variant4, Golden) {
    const Frame f = render(kGraph, {"line_width=1.2", "window=3", "overlay=false"}, helix_bundle_scene(), {160, 120}, 6.0);
    EXPECT_TRUE(matches_golden(f["final"], kHere + "/goldens/variant4_opacity.png"));
    // It is not variant 2's picture: the optimization cleared something.
    const Frame v2 = render(kSrc + "/graphs/variant2_oit_ao.json", {"line_width=1.2", "window=3", "overlay=false"},
                            helix_bundle_scene(), {160, 120}, 6.0);
    size_t lighter = 0;
    for (size_t i = 0; i < f["final"].pixels.size(); i += 4)
        lighter += f["final"].pixels[i] + f["final"].pixels[i + 1] + f["final"].pixels[i + 2] >
                   v2["final"].pixels[i] + v2["final"].pixels[i + 1] + v2["final"].pixels[i + 2] + 0.1f;
    EXPECT_GT(lighter, 100u) << "pixels where variant 4 shows more of the white background than variant 2";
}

// Under PATHLET_GL_LIMITS=minimum the engine holds the GL 4.5 minimum limits (8 image units, 8
// storage blocks a stage, none in geometry shaders, 8 combined output resources, ...) and checks
// every linked program against them: the graph must render the golden's picture there too.
// (tests/limits renders every shipped graph so; this is the golden's scene and size.)
TEST(Variant4, RendersTheGoldenUnderTheMinimumGlLimits) {
    ::setenv("PATHLET_GL_LIMITS", "minimum", 1);
    Frame f;
    try {
        f = render(kGraph, {"line_width=1.2", "window=3", "overlay=false"}, helix_bundle_scene(), {160, 120}, 6.0);
    } catch (const std::exception& e) {
        ::unsetenv("PATHLET_GL_LIMITS");
        FAIL() << e.what();
    }
    ::unsetenv("PATHLET_GL_LIMITS");
    EXPECT_TRUE(matches_golden(f["final"], kHere + "/goldens/variant4_opacity.png"));
}

TEST(Variant4, AHookThatReadsHookBufferNeedsItConnected) {
    try {
        render(kSrc + "/graphs/variant2_oit_ao.json", {"fill_list.color_hook=optimized_fade.glsl"}, helix_bundle_scene(),
               {64, 48}, 6.0);
        FAIL() << "rendered without the optimization's buffer";
    } catch (const std::exception& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("fill_list"), std::string::npos) << msg;
        EXPECT_NE(msg.find("hook_buffer"), std::string::npos) << msg;
    }
}
