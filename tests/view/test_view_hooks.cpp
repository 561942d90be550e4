// The viewer and hook files: the session watches a hook next to its graph, an edit
// rebuilds with the new hook, a broken edit keeps the last good graph and names the hook's
// file and line, and the hook's parameters are set like any pass parameter. Headless (the
// session runs on any GL context; the window only shows it).
#include "frame_capture.hpp"
#include "view/file_watch.hpp"
#include "view/view_session.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <thread>

using namespace pathlet;

namespace {

const std::string& dir() {
    static const std::string d = test_scratch_dir("pathlet_view_hooks");
    return d;
}

void write_hook(const std::string& tint, const std::string& extra = "") {
    std::ofstream(dir() + "/tint.frag") << "#version 450 core\n#include \"line_hooks.glsl\"\n"
                                        << "uniform float u_amount;  // @param 1 [0, 1] \"how much tint\"\n"
                                        << "vec4 line_color_hook(vec4 rgba, LinePoint p) {\n"
                                        << "    return vec4(mix(rgba.rgb, vec3(" << tint << "), u_amount), 1.0);" << extra
                                        << "\n}\n";
}

// Mean of each channel over covered pixels (alpha > 0.5) of the shown image.
glm::vec3 mean_colour(view::ViewSession& s, double t) {
    Executor& ex = s.executor();
    ex.run_frame({0, t, frame_bounds(two_speed_lines_scene().bounds(), {64, 48})});
    const Image img = read_resource(ex.texture(s.compiled().outputs.front().resource));
    glm::dvec3 sum(0);
    int n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (img.at(x, y, 3) > 0.5f) sum += glm::dvec3(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)), ++n;
    return n ? glm::vec3(sum / double(n)) : glm::vec3(-1);
}

}  // namespace

TEST(ViewHooks, AnEditedHookReloadsABrokenOneKeepsTheLastGoodGraph) {
    Runtime& rt = test_runtime();
    write_hook("0.0, 0.0, 1.0");
    const std::string graph = dir() + "/hooked.json";
    std::ofstream(graph) << R"({"version": 1, "resources": {"color": {"format": "rgba8"}},
      "passes": [{"name": "lines", "type": "gbuffer", "params": {"window": 0, "halo": 0, "color_hook": "tint.frag"},
                  "outputs": {"color": "color"}}], "outputs": [{"resource": "color"}]})";
    GpuScene gpu;
    gpu.upload(two_speed_lines_scene());
    view::ViewSession s(rt, gpu, {64, 48}, graph, {});
    const glm::vec3 blue = mean_colour(s, 5.0);
    EXPECT_GT(blue.b, 0.9f);
    EXPECT_LT(blue.g, 0.1f);

    // The hook is watched (it lies next to the graph); an edit shows as a change.
    const auto files = s.watched_files();
    EXPECT_NE(std::find(files.begin(), files.end(), dir() + "/tint.frag"), files.end());
    view::FileWatch watch;
    watch.watch(files);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // a new mtime even on coarse clocks
    write_hook("0.0, 1.0, 0.0", "  // now green");
    const auto changed = watch.changed();
    ASSERT_EQ(changed.size(), 1u);
    EXPECT_EQ(changed[0], dir() + "/tint.frag");
    ASSERT_TRUE(s.rebuild()) << s.error();
    const glm::vec3 green = mean_colour(s, 5.0);
    EXPECT_GT(green.g, 0.9f);
    EXPECT_LT(green.b, 0.1f);

    // The hook's parameter, as the panels set it: amount 0 is the plain colour map.
    ASSERT_TRUE(s.set("lines.amount", "0")) << s.error();
    const glm::vec3 plain = mean_colour(s, 5.0);
    EXPECT_GT(glm::length(plain - green), 0.3f);
    EXPECT_FALSE(s.set("lines.amuont", "0"));
    EXPECT_NE(s.error().find("did you mean 'amount'"), std::string::npos) << s.error();

    // A broken edit: the error names the hook and its line, the last good graph keeps running.
    write_hook("0.0, 1.0, 0.0", " syntax error here");
    EXPECT_FALSE(s.rebuild());
    EXPECT_NE(s.error().find("tint.frag:5:"), std::string::npos) << s.error();
    const glm::vec3 still = mean_colour(s, 5.0);
    EXPECT_NEAR(still.g, plain.g, 1e-6f);
}
