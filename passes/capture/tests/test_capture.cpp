// The capture pass goes through the render's asynchronous output side (PassContext::write_image:
// a pixel-pack copy in the frame, the file encoded on a writer and renamed into place once
// whole), so its files must be those of the graph's own output captures of the same resources,
// byte for byte (test_async_output checks those against the synchronous path): float maps as
// EXR in their own format (r16f AO, rgba16f normal+depth, the depth texture), colour as PNG.
#include "file_bytes.hpp"
#include "frame_capture.hpp"
#include "renderer.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace pathlet {
namespace {

namespace fs = std::filesystem;


TEST(Capture, ThePassWritesTheBytesTheGraphsOutputCapturesWrite) {
    const fs::path dir = fs::path(test_scratch_dir("pathlet_capture_pass")) / "run";
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ifstream in(std::string(PATHLET_SOURCE_DIR) + "/graphs/lineao_debug.json");
    nlohmann::json g = nlohmann::json::parse(in, nullptr, true, true);
    const std::vector<std::pair<std::string, std::string>> maps = {
        {"ao", "exr"}, {"normal_depth", "exr"}, {"depth", "exr"}, {"color", "png"}};
    g["outputs"] = nlohmann::json::array();
    for (const auto& [res, ext] : maps) {
        g["passes"].push_back({{"name", "save_" + res},
                               {"type", "capture"},
                               {"params", {{"path", (dir / "pass" / (res + "_{frame:03}." + ext)).string()}}},
                               {"inputs", {{"src", res}}}});
        g["outputs"].push_back({{"resource", res}, {"capture", (dir / "graph" / (res + "_{frame:03}." + ext)).string()}});
    }
    const fs::path graph = dir / "capture_debug.json";
    std::ofstream(graph) << g.dump(2);

    RenderOptions o;
    o.graph_path = graph.string();
    o.sets = {"window=3"};
    o.size = {64, 48};
    o.time = {4.0, 5.0, 0.5};  // 3 frames
    o.out_dir = dir.string();
    o.quiet = true;
    o.warmup = 0;
    render(test_runtime(), helix_bundle_scene(), o);
    for (const auto& [res, ext] : maps)
        for (int f = 0; f < 3; ++f) {
            char name[64];
            std::snprintf(name, sizeof name, "%s_%03d.%s", res.c_str(), f, ext.c_str());
            const fs::path mine = dir / "pass" / name, theirs = dir / "graph" / name;
            ASSERT_TRUE(fs::exists(mine)) << mine;
            ASSERT_TRUE(fs::exists(theirs)) << theirs;
            expect_same_frame_file(mine, theirs);
        }
    for (const auto& e : fs::directory_iterator(dir / "pass"))
        EXPECT_NE(e.path().filename().string()[0], '.') << "a temp file stayed: " << e.path();
}

}  // namespace
}  // namespace pathlet
