// `pathlet view` in a real window under a private Xvfb: its screenshot is the headless render
// of the same frame, a --set changes it as for render, no display is a clear error.
#include "../support/optional_tool.hpp"
#include "../support/xvfb.hpp"
#include "image_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace pathlet;

namespace {
std::string src(const std::string& p) { return std::string(PATHLET_SOURCE_DIR) + "/" + p; }
fs::path work() {
    fs::path d = fs::path(PATHLET_TEST_BINARY_DIR) / ("view_runs_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}
int cli(const std::string& args, std::string* err = nullptr, const std::string& env = "") {
    fs::path e = work() / "err.txt";
    int status = std::system((env + " " + std::string(PATHLET_CLI) + " " + args + " >/dev/null 2>" + e.string() + " </dev/null").c_str());
    if (err) {
        std::ifstream in(e);
        std::stringstream ss;
        ss << in.rdbuf();
        *err = ss.str();
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}
double max_diff(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size()) return 1e9;
    double m = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) m = std::max(m, double(std::fabs(a.pixels[i] - b.pixels[i])));
    return m;
}
const std::string kScene = src("graphs/demo_blur.json") + " --data " + src("tests/engine/data/two_lines.vtk") +
                           " --size 320x180 --time 0";
}  // namespace

TEST(ViewCli, ScreenshotEqualsHeadlessRenderAndSetChangesIt) {
    PATHLET_REQUIRE_TOOLS("Xvfb");
    test::Xvfb x;
    ASSERT_TRUE(x.ok()) << "Xvfb did not start";
    fs::path d = work();
    std::string err;
    ASSERT_EQ(cli("view " + kScene + " --exit-after 2 --screenshot " + (d / "view.png").string(), &err), 0) << err;
    ASSERT_EQ(cli("render " + kScene + " --quiet --out " + (d / "r").string(), &err), 0) << err;
    Image view = read_image((d / "view.png").string());
    Image ref = read_image((d / "r/demo_blur/00000.png").string());
    EXPECT_LE(max_diff(view, ref), 1.0 / 255.0) << "window screenshot differs from the headless render";

    ASSERT_EQ(cli("view " + kScene + " --set radius=0 --exit-after 1 --screenshot " + (d / "sharp.png").string(), &err), 0) << err;
    ASSERT_EQ(cli("render " + kScene + " --set radius=0 --quiet --out " + (d / "r0").string(), &err), 0) << err;
    Image sharp = read_image((d / "sharp.png").string());
    EXPECT_GT(max_diff(sharp, view), 0.05) << "--set radius=0 did not change the image";
    EXPECT_LE(max_diff(sharp, read_image((d / "r0/demo_blur/00000.png").string())), 1.0 / 255.0);
    fs::remove_all(d);
}

TEST(ViewCli, NoDisplayIsAClearError) {
    std::string err;
    int code = cli("view " + kScene + " --exit-after 1", &err);  // ctest clears DISPLAY
    EXPECT_NE(code, 0);
    EXPECT_LT(code, 128) << "crashed instead of reporting: " << err;
    EXPECT_NE(err.find("no display"), std::string::npos) << err;
    fs::remove_all(work());
}

// The mouse camera and the keys, driven by a script: an orbit and a zoom change the picture
// and the s key writes the graph output; --time starts paused (two runs of different length
// show the same frame) and space plays (the clock moves, so the picture does).
TEST(ViewCli, ScriptedOrbitZoomPlayAndScreenshotKey) {
    PATHLET_REQUIRE_TOOLS("Xvfb");
    test::Xvfb x;
    ASSERT_TRUE(x.ok()) << "Xvfb did not start";
    fs::path d = work();
    const std::string scene = "variant1_lineao --phantom small --size 160x90 --time 2";  // inside 0..4 s
    auto shot = [&](const std::string& name, const std::string& script, int frames) {
        std::string args = "view " + scene + " --exit-after " + std::to_string(frames) + " --screenshot " + (d / name).string();
        if (!script.empty()) {
            std::ofstream(d / (name + ".json")) << script;
            args += " --script " + (d / (name + ".json")).string() + " --screenshot-dir " + d.string();
        }
        std::string err;
        EXPECT_EQ(cli(args, &err), 0) << err;
        return read_image((d / name).string());
    };
    Image plain = shot("plain.png", "", 2);
    Image paused_longer = shot("paused.png", "", 4);
    EXPECT_LE(max_diff(plain, paused_longer), 1.0 / 255.0) << "--time should start paused";
    Image orbit = shot("orbit.png", R"([{"frame": 0, "drag": [80, 0], "button": "left"}, {"frame": 1, "key": "s"}])", 2);
    EXPECT_GT(max_diff(plain, orbit), 0.2) << "a left drag did not turn the camera";
    ASSERT_TRUE(fs::exists(d / "pathlet_view_00001.png")) << "the s key wrote no screenshot";
    EXPECT_LE(max_diff(read_image((d / "pathlet_view_00001.png").string()), orbit), 1.0 / 255.0);
    Image zoom = shot("zoom.png", R"([{"frame": 0, "scroll": 3}])", 1);
    EXPECT_GT(max_diff(plain, zoom), 0.2) << "the wheel did not zoom";
    Image played = shot("played.png", R"([{"frame": 0, "key": "space"}, {"frame": 0, "key": "up"}])", 8);
    EXPECT_GT(max_diff(plain, played), 0.05) << "space did not start the clock";
    fs::remove_all(d);
}

TEST(ViewCli, BadScriptIsAClearErrorNamingFileAndEvent) {
    fs::path d = work();
    std::ofstream(d / "bad.json") << R"([{"frame": 0, "key": "space"}, {"frame": 1, "key": "f13"}])";
    std::string err;
    int code = cli("view " + kScene + " --exit-after 1 --script " + (d / "bad.json").string(), &err);
    EXPECT_NE(code, 0);
    EXPECT_LT(code, 128) << err;
    EXPECT_NE(err.find("bad.json:/1"), std::string::npos) << err;
    EXPECT_NE(err.find("\"key\" must be one of"), std::string::npos) << err;
    fs::remove_all(d);
}

TEST(ViewCli, ScriptedParameterChangeEqualsSetAndShowsInTheWindow) {
    PATHLET_REQUIRE_TOOLS("Xvfb");
    test::Xvfb x;
    ASSERT_TRUE(x.ok()) << "Xvfb did not start";
    fs::path d = work();
    std::ofstream(d / "set.json") << R"([{"frame": 1, "set": "radius=0"}])";
    std::string err;
    ASSERT_EQ(cli("view " + kScene + " --exit-after 3 --script " + (d / "set.json").string() + " --screenshot " +
                      (d / "live.png").string() + " --screenshot-window " + (d / "window.png").string(),
                  &err),
              0)
        << err;
    ASSERT_EQ(cli("render " + kScene + " --set radius=0 --quiet --out " + (d / "rs").string(), &err), 0) << err;
    Image live = read_image((d / "live.png").string());
    Image ref = read_image((d / "rs/demo_blur/00000.png").string());
    EXPECT_LE(max_diff(live, ref), 1.0 / 255.0) << "a parameter set in the running view must equal --set";
    // The window screenshot has the panels over the output: same size, not the same pixels.
    Image window = read_image((d / "window.png").string());
    EXPECT_EQ(window.width, live.width);
    EXPECT_GT(max_diff(window, live), 0.2) << "no panels in the window";
}

TEST(ViewCli, BrokenGraphKeepsTheLastGoodImageAndReportsTheError) {
    PATHLET_REQUIRE_TOOLS("Xvfb");
    test::Xvfb x;
    ASSERT_TRUE(x.ok()) << "Xvfb did not start";
    fs::path d = work();
    {  // the shipped graph with a typo in a pass type, as an edit would leave it
        std::ifstream in(src("graphs/demo_blur.json"));
        std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        s.replace(s.find("\"type\": \"blur\""), 14, "\"type\": \"blurr\"");
        std::ofstream(d / "broken.json") << s;
    }
    std::ofstream(d / "switch.json") << R"([{"frame": 1, "graph": ")" + (d / "broken.json").string() + R"("}])";
    std::string err;
    EXPECT_EQ(cli("view " + kScene + " --exit-after 3 --script " + (d / "switch.json").string() + " --screenshot " +
                      (d / "kept.png").string(),
                  &err),
              1)
        << "a scripted change that failed ends with 1";
    EXPECT_NE(err.find("broken.json"), std::string::npos) << err;
    EXPECT_NE(err.find("blurr"), std::string::npos) << err;
    EXPECT_NE(err.find("last good graph"), std::string::npos) << err;
    ASSERT_EQ(cli("render " + kScene + " --quiet --out " + (d / "good").string(), &err), 0) << err;
    EXPECT_LE(max_diff(read_image((d / "kept.png").string()), read_image((d / "good/demo_blur/00000.png").string())),
              1.0 / 255.0)
        << "the last good graph must keep running";
}

// Graph switching follows the trust rule: a graph naming an untrusted plugin folder
// is refused with the command that trusts it, the last good graph keeps running, and the
// folder's plugin is never opened (its constructor would write the marker file).
TEST(ViewCli, SwitchingToAGraphWithAnUntrustedPluginFolderLoadsNothing) {
    PATHLET_REQUIRE_TOOLS("Xvfb");
    test::Xvfb x;
    ASSERT_TRUE(x.ok()) << "Xvfb did not start";
    fs::path d = work();
    fs::create_directories(d / "plugins");
    fs::copy_file(std::string(PATHLET_FIXTURE_DIR) + "/pathlet_marker_pass.so", d / "plugins" / "pathlet_marker.so",
                  fs::copy_options::overwrite_existing);
    std::ofstream(d / "untrusted.json") << R"({"version": 1, "plugin_dirs": ["plugins"],
      "passes": [{"name": "m", "type": "fixture_marker"}], "outputs": [{"resource": "m.color"}]})";
    std::ofstream(d / "switch.json") << R"([{"frame": 1, "graph": ")" + (d / "untrusted.json").string() + R"("}])";
    const fs::path marker = d / "constructor_ran.txt";
    std::string err;
    EXPECT_EQ(cli("view " + kScene + " --exit-after 3 --script " + (d / "switch.json").string() +
                      " --screenshot " + (d / "kept.png").string(),
                  &err, "PATHLET_FIXTURE_MARKER='" + marker.string() + "' XDG_CONFIG_HOME='" + (d / "config").string() + "'"),
              1)
        << err;
    EXPECT_NE(err.find("is not trusted"), std::string::npos) << err;
    EXPECT_NE(err.find("pathlet trust " + fs::canonical(d / "plugins").string()), std::string::npos) << err;
    EXPECT_NE(err.find("last good graph"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(marker)) << "the untrusted plugin was loaded";
    EXPECT_TRUE(fs::exists(d / "kept.png"));
    fs::remove_all(d);
}

// The panels leave the overlay's time label (top left) to be read (they covered it).
TEST(ViewCli, ThePanelsLeaveTheTimeLabelVisible) {
    PATHLET_REQUIRE_TOOLS("Xvfb");
    test::Xvfb x;
    ASSERT_TRUE(x.ok()) << "Xvfb did not start";
    fs::path d = work();
    std::string err;
    ASSERT_EQ(cli("view variant1_lineao --phantom small --size 640x360 --time 1 --exit-after 3 --screenshot " +
                      (d / "live.png").string() + " --screenshot-window " + (d / "window.png").string(),
                  &err),
              0)
        << err;
    const Image live = read_image((d / "live.png").string()), window = read_image((d / "window.png").string());
    ASSERT_EQ(window.width, live.width);
    double label = 0, panels = 0;
    for (int y = 0; y < live.height; ++y)
        for (int xx = 0; xx < live.width; ++xx)
            for (int c = 0; c < 3; ++c) {
                const double diff = std::fabs(window.at(xx, y, c) - live.at(xx, y, c));
                if (xx < live.width / 4 && y < live.height / 10) label = std::max(label, diff);  // "t = 1.00 s"
                else panels = std::max(panels, diff);
            }
    EXPECT_LE(label, 1.0 / 255.0) << "a panel covers the time label";
    EXPECT_GT(panels, 0.2) << "no panels in the window";
    fs::remove_all(d);
}
