// Executor error paths and history resources, through real graphs on llvmpipe.
#include "engine_test_util.hpp"

using namespace pathlet;
using namespace pathlet::testing_util;

namespace {

std::string render_error(const std::string& graph, std::vector<std::string> sets = {}) {
    Runtime& rt = runtime();
    try {
        rt.host.load_file(std::string(PATHLET_FIXTURE_DIR) + "/pathlet_good_pass.so");
    } catch (const PluginError&) {
        // already loaded by an earlier test
    }
    try {
        render_resource(graph, "x", {32, 32}, std::move(sets));
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Executor, ExceptionInExecuteNamesThePass) {
    std::string msg = render_error(test_file("graphs/errors.json"));
    EXPECT_NE(msg.find("pass 'boom' (fixture_throw)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("deliberate failure in execute"), std::string::npos) << msg;
    EXPECT_NE(msg.find("frame 0"), std::string::npos) << msg;
}

TEST(Executor, ExceptionInSetupNamesThePass) {
    std::string msg = render_error(test_file("graphs/errors.json"), {"where=true"});
    EXPECT_NE(msg.find("pass 'boom'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("failed in setup"), std::string::npos) << msg;
}

TEST(Executor, GlErrorIsReportedWithThePass) {
    std::string msg = render_error(test_file("graphs/glerror.json"));
    EXPECT_NE(msg.find("pass 'bad_gl' caused OpenGL errors"), std::string::npos) << msg;
    EXPECT_NE(msg.find("glBindTexture"), std::string::npos) << msg;
    // The context is usable afterwards: a good graph still renders.
    Image img = render_resource(source("graphs/demo_blur.json"), "blurred", {16, 16});
    EXPECT_EQ(img.width, 16);
    EXPECT_TRUE(runtime().gl->take_errors().empty());
}

TEST(Executor, AGlErrorNoCallbackReportedIsCaughtAtTheEndOfTheRun) {
    // glGetError is not asked every frame (a round trip to a threaded driver): an error that
    // reaches no debug callback (a driver that reports none) is caught once, at the end.
    render_error(test_file("graphs/glerror.json"));  // the fixture plugin loaded
    RenderOptions o;  // nothing read back in the frames (read_texture would clear glGetError)
    o.graph_path = test_file("graphs/glerror.json");
    o.size = {32, 32};
    o.warmup = 0;
    o.write_images = false;
    o.quiet = true;
    o.time = {0, 2, 1};
    glDebugMessageControl(GL_DEBUG_SOURCE_API, GL_DEBUG_TYPE_ERROR, GL_DONT_CARE, 0, nullptr, GL_FALSE);
    std::string msg;
    try {
        render(runtime(), tiny_scene(), o);
    } catch (const std::exception& e) {
        msg = e.what();
    }
    glDebugMessageControl(GL_DEBUG_SOURCE_API, GL_DEBUG_TYPE_ERROR, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    EXPECT_NE(msg.find("caused OpenGL errors in the run"), std::string::npos) << msg;
    EXPECT_NE(msg.find("glGetError 0x05"), std::string::npos) << msg;
    EXPECT_TRUE(runtime().gl->take_errors().empty());
}

TEST(Executor, ShaderCompileErrorNamesFileAndLine) {
    std::string msg = render_error(test_file("graphs/broken_shader.json"));
    EXPECT_NE(msg.find("pass 'pattern'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("broken.frag:6:"), std::string::npos) << msg;  // the line after the missing ';'
}

TEST(Executor, HistoryResourceHoldsThePreviousFrame) {
    for (int frames : {1, 3, 5}) {
        Image img = render_resource(test_file("graphs/history.json"), "acc", {8, 8}, {}, frames);
        ASSERT_EQ(img.width, 8);
        // frame 0 reads a zeroed history; every frame adds 10/255.
        EXPECT_NEAR(img.pixels[0], frames * 10.0 / 255.0, 0.5 / 255.0) << "after " << frames << " frames";
        EXPECT_NEAR(img.pixels[4 * 63 + 3], std::min(1.0, frames * 10.0 / 255.0), 0.5 / 255.0);
    }
}

TEST(Executor, UnknownResourceIsAClearError) {
    Scene scene = tiny_scene();
    GraphFile g = parse_graph_file(source("graphs/demo_blur.json"));
    CompiledGraph cg = compile_graph(g, runtime().registry, {16, 16});
    GpuScene gpu;
    gpu.upload(scene);
    Executor e(*runtime().gl, cg, gpu);
    e.setup();
    e.run_frame({0, 0.0, Camera{}});
    try {
        e.texture("no_such_thing");
        FAIL() << "expected an error";
    } catch (const PassError& err) {
        EXPECT_NE(std::string(err.what()).find("no_such_thing"), std::string::npos);
    }
}

TEST(GpuSceneTest, AutoLineWidthFollowsTheDataSizeAndRangesClipToTheWindow) {
    runtime();  // a current GL context
    Scene scene = tiny_scene();  // x 0..4, y 0..1: diagonal sqrt(17)
    GpuScene gpu;
    gpu.upload(scene);
    EXPECT_NEAR(gpu.auto_line_width(), 0.005f * std::sqrt(17.0f), 1e-6f);
    EXPECT_FLOAT_EQ(gpu.line_width(0.0f), gpu.auto_line_width());
    EXPECT_FLOAT_EQ(gpu.line_width(0.7f), 0.7f);
    // Times 0..4 per line: the window [1.5, 2.5] keeps segments 1-2 and 2-3 of both lines.
    GpuScene::Ranges r;
    gpu.ranges(1.5, 2.5, r);
    ASSERT_EQ(r.first.size(), 2u);
    EXPECT_EQ(r.first[0], 1);
    EXPECT_EQ(r.count[0], 3);
    EXPECT_EQ(r.segments, 4u);
    gpu.ranges(0, 0, r);  // no window: every line whole
    EXPECT_EQ(r.segments, 8u);
    gpu.ranges(10, 11, r);  // after the data: nothing
    EXPECT_TRUE(r.first.empty());
}
