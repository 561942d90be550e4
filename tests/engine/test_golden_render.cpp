// A small real graph (full-screen pattern -> separable blur) against a golden image, plus
// the properties a golden cannot show: determinism, culling, a capture side-effect pass.
#include "engine_test_util.hpp"
#include "golden.hpp"

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace pathlet;
using namespace pathlet::testing_util;

TEST(GoldenRender, DemoBlurMatchesGolden) {
    Image img = render_resource(source("graphs/demo_blur.json"), "blurred", {96, 64});
    EXPECT_TRUE(matches_golden(img, test_file("goldens/demo_blur.png")));
}

TEST(GoldenRender, BlurRadiusChangesTheImageAndRenderIsDeterministic) {
    Image a = render_resource(source("graphs/demo_blur.json"), "blurred", {96, 64});
    Image b = render_resource(source("graphs/demo_blur.json"), "blurred", {96, 64});
    Image sharp = render_resource(source("graphs/demo_blur.json"), "blurred", {96, 64}, {"radius=0"});
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_NE(a.pixels, sharp.pixels);
    // Blurring lowers the total variation of the image.
    auto variation = [](const Image& im) {
        double v = 0;
        for (int y = 0; y < im.height; ++y)
            for (int x = 1; x < im.width; ++x)
                v += std::abs(im.pixels[size_t(4 * (y * im.width + x))] - im.pixels[size_t(4 * (y * im.width + x - 1))]);
        return v;
    };
    EXPECT_LT(variation(a), 0.8 * variation(sharp));
}

TEST(GoldenRender, UnusedPassIsCulledWithAReason) {
    GraphFile g = parse_graph_file(source("graphs/demo_blur.json"));
    CompiledGraph cg = compile_graph(g, runtime().registry, {64, 64});
    ASSERT_EQ(cg.culled.size(), 1u);
    EXPECT_EQ(cg.culled[0].name, "unused");
    EXPECT_FALSE(cg.culled[0].reason.empty());
    // The blur's unbound `tmp` output became an implicit transient.
    EXPECT_GE(cg.find_resource("soft.tmp"), 0);
}

TEST(GoldenRender, CapturePassWritesFilesAndIsNeverCulled) {
    fs::path dir = fs::path(PATHLET_TEST_BINARY_DIR) / "capture_out";
    fs::remove_all(dir);
    std::ifstream in(test_file("graphs/capture_pass.json"));
    std::string text((std::istreambuf_iterator<char>(in)), {});
    text.replace(text.find("CAPTURE_DIR"), 11, dir.string());
    fs::path graph = fs::path(PATHLET_TEST_BINARY_DIR) / "capture_pass.json";
    std::ofstream(graph) << text;
    render_resource(graph.string(), "pattern", {16, 16}, {}, 2);
    EXPECT_TRUE(fs::exists(dir / "save_000.png"));
    EXPECT_TRUE(fs::exists(dir / "save_001.png"));
    Image saved = read_image((dir / "save_001.png").string());
    EXPECT_EQ(saved.width, 16);
}

TEST(GoldenRender, UnboundOptionalOutputGetsNoResource) {
    // gbuffer's line_id is optional: variant 1 leaves it unbound, gbuffer_only binds it.
    CompiledGraph v1 = compile_graph(parse_graph_file(source("graphs/variant1_lineao.json")), runtime().registry, {64, 64});
    EXPECT_LT(v1.find_resource("gbuffer.line_id"), 0);
    EXPECT_LT(v1.find_resource("line_id"), 0);
    CompiledGraph gb = compile_graph(parse_graph_file(source("graphs/gbuffer_only.json")), runtime().registry, {64, 64});
    EXPECT_GE(gb.find_resource("line_id"), 0);
}
