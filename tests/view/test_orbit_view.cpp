// The camera and clock of `pathlet view` without a window: orbit keeps the distance and turns
// the eye, pan moves eye and target together, zoom scales the distance, reset restores the
// render's framing; playback loops, stops at the end without loop, scrubs within the span.
#include "view/file_watch.hpp"
#include "view/orbit_view.hpp"
#include "view/panel_values.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <unistd.h>

using namespace pathlet;

namespace {
const Bounds kBox{glm::vec3(-10, -20, -5), glm::vec3(10, 20, 5)};
const glm::ivec2 kSize{320, 180};
float dist(const Camera& c) { return glm::length(c.eye - c.target); }
}  // namespace

TEST(OrbitView, OrbitTurnsTheEyeAtTheSameDistanceAndResetRestores) {
    const Camera framing = frame_bounds(kBox, kSize);
    view::OrbitView v(framing, kBox, kSize);
    v.orbit(100, 0);  // 40 degrees about the up axis
    const Camera& c = v.camera();
    EXPECT_NEAR(dist(c), dist(framing), 1e-3f * dist(framing));
    const glm::vec3 a = glm::normalize(framing.eye - framing.target), b = glm::normalize(c.eye - c.target);
    EXPECT_NEAR(glm::degrees(std::acos(glm::clamp(glm::dot(a, b), -1.0f, 1.0f))), 40.0f, 0.5f);
    EXPECT_NE(c.view, framing.view);
    v.reset();
    EXPECT_EQ(v.camera().eye, framing.eye);
    EXPECT_EQ(v.camera().view, framing.view);
}

TEST(OrbitView, TiltStopsShortOfThePoles) {
    view::OrbitView v(frame_bounds(kBox, kSize), kBox, kSize);
    for (int i = 0; i < 50; ++i) v.orbit(0, 40);  // 800 degrees of tilt asked for
    const Camera& c = v.camera();
    EXPECT_LT(std::fabs(glm::dot(glm::normalize(c.eye - c.target), glm::normalize(c.up))), 0.99f);
}

TEST(OrbitView, PanMovesEyeAndTargetTogetherAndZoomScalesTheDistance) {
    const Camera framing = frame_bounds(kBox, kSize);
    view::OrbitView v(framing, kBox, kSize);
    v.pan(30, -10);
    EXPECT_GT(glm::length(v.camera().target - framing.target), 0.0f);
    EXPECT_NEAR(glm::length((v.camera().eye - framing.eye) - (v.camera().target - framing.target)), 0.0f, 1e-4f);
    const float d = dist(v.camera());
    v.zoom(2);
    EXPECT_NEAR(dist(v.camera()), d / (1.15f * 1.15f), 1e-3f * d);
    v.zoom(-1000);  // clamped far away, never infinite
    EXPECT_LE(dist(v.camera()), 100.0f * kBox.radius() * 1.001f);
}

TEST(Playback, LoopsStopsAndScrubsWithinTheSpan) {
    view::Playback p;
    p.t_min = 2, p.t_max = 6, p.t = 5, p.playing = true;
    p.advance(2.0);  // 7 -> wraps to 3
    EXPECT_NEAR(p.t, 3.0, 1e-9);
    p.loop = false;
    p.speed = 4.0;
    p.advance(1.0);  // 7 -> stops at the end
    EXPECT_NEAR(p.t, 6.0, 1e-9);
    EXPECT_FALSE(p.playing);
    p.advance(1.0);
    EXPECT_NEAR(p.t, 6.0, 1e-9);  // paused: no change
    p.scrub(-10);
    EXPECT_NEAR(p.t, 2.0, 1e-9);
}

TEST(FileWatch, ReportsWrittenAppearingAndVanishingFilesOnce) {
    const std::filesystem::path d = std::filesystem::temp_directory_path() / ("pathlet_watch_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    const std::string a = (d / "a.json").string(), b = (d / "b.frag").string();
    std::ofstream(a) << "{}";
    pathlet::view::FileWatch w;
    w.watch({a, b});
    EXPECT_TRUE(w.changed().empty()) << "nothing happened yet";
    std::ofstream(a) << "{\"x\": 1}";  // another size: a change even within the mtime's resolution
    EXPECT_EQ(w.changed(), std::vector<std::string>{a});
    EXPECT_TRUE(w.changed().empty()) << "reported once";
    std::ofstream(b) << "void main() {}";
    EXPECT_EQ(w.changed(), std::vector<std::string>{b});
    std::filesystem::remove(a);
    EXPECT_EQ(w.changed(), std::vector<std::string>{a});
    const auto files = pathlet::view::graph_and_shader_files(a, {d.string()});
    EXPECT_NE(std::find(files.begin(), files.end(), b), files.end()) << "shader files of the folders are watched";
    std::filesystem::remove_all(d);
}

// An "auto" slider (0 or below) shows the value the pass uses, which it reports as a stat named
// like the parameter; a value set by hand shows as it is (auto sliders showed 0).
TEST(PanelValues, AutoSlidersShowTheValueInUse) {
    const view::InUse in_use = {{"line_width", 1.109375}, {"overlay.speed_min", 13.86}, {"overlay.font_px", 18}};
    EXPECT_EQ(view::slider_format("line_width", 0.0, false, in_use), "auto (1.109)");
    EXPECT_EQ(view::slider_format("overlay.speed_min", 0.0, false, in_use), "auto (13.86)");
    EXPECT_EQ(view::slider_format("overlay.speed_min", -1.0, false, in_use), "auto (13.86)");
    EXPECT_EQ(view::slider_format("overlay.font_px", 0.0, true, in_use), "auto (18)");
    EXPECT_EQ(view::slider_format("line_width", 2.5, false, in_use), "%.4g") << "set by hand";
    EXPECT_EQ(view::slider_format("window", 0.0, false, in_use), "%.4g") << "no value in use reported";
}
