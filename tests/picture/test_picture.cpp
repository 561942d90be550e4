// The study's picture on real GL (llvmpipe): edge_aa against a 4x4 supersampled render of the
// same graph (the RMS and speckle targets, on tiny scenes), halos as a supersampled render
// draws them at every line width from 1 to 20 px, the overlay (golden, time label,
// legend, a missing or bad font) and `render --ssaa` (size, box filter).
#include "frame_capture.hpp"
#include "golden.hpp"
#include "image_io.hpp"
#include "image_metrics.hpp"
#include "image_probes.hpp"
#include "renderer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#ifndef BUNDLE_W
#define BUNDLE_W 320
#define BUNDLE_H 240
#endif

using namespace pathlet;
using quality::AaFigures;
using quality::aa_figures;

namespace {

const std::string kSrc = PATHLET_SOURCE_DIR;
const std::string kHere = PATHLET_TEST_SOURCE_DIR;

std::string scratch(const std::string& name) { return test_scratch_dir("pathlet_picture") + "/" + name; }
const std::string& square_camera() {
    static const std::string path = write_square_on_camera(scratch("camera.json"));
    return path;
}

// Three straight lines through (5, 2) at 8, 33 and 71 degrees, at z = -1, 0, 1, so they cross
// in front of one another: edges against the background and against lines behind.
const Scene& slanted_lines_scene() {
    static const Scene scene = [] {
        Scene s;
        const float angles[3] = {8.0f, 33.0f, 71.0f};
        for (int i = 0; i < 3; ++i) {
            const float a = glm::radians(angles[i]);
            const glm::vec3 dir(std::cos(a), std::sin(a), 0.0f);
            LineRange r{uint32_t(s.lines.position.size()), 101};
            for (int k = 0; k <= 100; ++k) {
                const float u = float(k) / 100.0f;
                s.lines.position.push_back(glm::vec3(5.0f, 2.0f, float(i - 1)) + (u - 0.5f) * 16.0f * dir);
                s.lines.velocity.push_back(dir * (1.0f + 2.0f * float(i)));
                s.lines.time.push_back(10.0f * u);
            }
            s.lines.lines.push_back(r);
        }
        s.source = "three slanted straight lines (tests/picture)";
        return s;
    }();
    return scene;
}

// Twelve short dashes (three times as long as wide at line_width 1.1: 11 by 3.7 pixels at 72 rows
// square on) at angles 7..84 degrees on a 4x3 grid around (5, 2), off the pixel grid by a little
// more each: a good share of every edge is a dash's end, which only the end's own coverage smooths.
const Scene& dashes_scene() {
    static const Scene scene = [] {
        Scene s;
        for (int i = 0; i < 12; ++i) {
            const float a = glm::radians(7.0f + 7.0f * float(i));
            const glm::vec3 dir(std::cos(a), std::sin(a), 0.0f);
            const glm::vec3 centre(5.0f + 5.0f * (float(i % 4) - 1.5f) + 0.041f * float(i), 2.0f + 5.0f * float(i / 4 - 1), 0.0f);
            LineRange r{uint32_t(s.lines.position.size()), 11};
            for (int k = 0; k <= 10; ++k) {
                const float u = float(k) / 10.0f;
                s.lines.position.push_back(centre + (u - 0.5f) * 3.3f * dir);
                s.lines.velocity.push_back(dir);
                s.lines.time.push_back(10.0f * u);
            }
            s.lines.lines.push_back(r);
        }
        s.source = "twelve short dashes (tests/picture)";
        return s;
    }();
    return scene;
}

// One frame of a shipped graph, box-filtered back to `size` when supersampled.
Image render_image(const Scene& scene, const std::string& graph, std::vector<std::string> sets, glm::ivec2 size,
                   int ssaa = 1, const std::string& resource = "final", bool square_on = true, double t = 5.0) {
    RenderOptions opt;
    opt.graph_path = kSrc + "/graphs/" + graph + ".json";
    opt.sets = std::move(sets);
    opt.size = size;
    opt.ssaa = ssaa;
    opt.time.start = t;
    if (square_on) opt.camera_path = square_camera();
    Frame f = render_frame(test_runtime(), scene, opt, {resource});
    return box_downsample(f[resource], ssaa);
}

}  // namespace

// The edge targets' measurement on tiny scenes: the frame against the same graph rendered 4x4 larger
// (LineAO radii and filter widths scaled) and box-filtered, whose 16 samples are the ground
// truth. Hard edges are today's picture; edge_aa must get much closer, without speckles.
TEST(EdgeAA, SlantedLinesAreCloserToTheSupersampledFrame) {
    const std::vector<std::string> sets{"overlay=false", "window=0", "line_width=0.5"};
    auto with = [&](std::vector<std::string> more) {
        std::vector<std::string> s = sets;
        s.insert(s.end(), more.begin(), more.end());
        return s;
    };
    const glm::ivec2 size{96, 72};
    const Image ref = render_image(slanted_lines_scene(), "variant1_lineao", with({"aa=false"}), size, 4);
    const Image hard = render_image(slanted_lines_scene(), "variant1_lineao", with({"aa=false"}), size);
    const Image soft = render_image(slanted_lines_scene(), "variant1_lineao", sets, size);
    const AaFigures h = aa_figures(hard, ref), s = aa_figures(soft, ref);
    std::printf("slanted lines: RMS vs 4x4 supersampled: hard edges %.1f, edge_aa %.1f (%.0f %%)\n", h.rms, s.rms,
                100.0 * s.rms / h.rms);
    EXPECT_GT(h.rms, 10.0) << "the scene must have aliased edges to smooth";
    EXPECT_LE(s.rms, 0.45 * h.rms);
    EXPECT_LE(s.speckle, 0.003);
    EXPECT_FALSE(has_nan(soft));
}

// The ends are edges too: the same measure on short dashes, where the coverage of a dash's end
// (line_edge's cap, line_coverage's end term) carries much of the frame's error. Without it the
// ends step as hard edges do.
TEST(EdgeAA, DashEndsAreCloserToTheSupersampledFrame) {
    const std::vector<std::string> sets{"overlay=false", "window=0", "line_width=1.1"};
    auto with = [&](const std::string& more) {
        std::vector<std::string> s = sets;
        s.push_back(more);
        return s;
    };
    const glm::ivec2 size{128, 72};
    const Image ref = render_image(dashes_scene(), "variant1_lineao", with("aa=false"), size, 4);
    const Image hard = render_image(dashes_scene(), "variant1_lineao", with("aa=false"), size);
    const Image soft = render_image(dashes_scene(), "variant1_lineao", sets, size);
    const AaFigures h = aa_figures(hard, ref), s = aa_figures(soft, ref);
    if (const char* dir = std::getenv("PATHLET_PICTURE_DUMP")) {  // for looking at the images
        write_image(std::string(dir) + "/dashes_ref.png", ref);
        write_image(std::string(dir) + "/dashes_hard.png", hard);
        write_image(std::string(dir) + "/dashes_soft.png", soft);
    }
    std::printf("dashes: RMS vs 4x4 supersampled: hard edges %.1f, edge_aa %.1f (%.0f %%); speckles %.4f\n", h.rms, s.rms,
                100.0 * s.rms / h.rms, s.speckle);
    EXPECT_GT(h.rms, 10.0) << "the scene must have aliased edges to smooth";
    // 41 % with the ends smoothed, 55 % without (edges along the sides only).
    EXPECT_LE(s.rms, 0.47 * h.rms);
    EXPECT_LE(s.speckle, 0.003);
    EXPECT_FALSE(has_nan(soft));
}

TEST(EdgeAA, DenseBundleGetsCloserAndStaysDarkInside) {
    const std::vector<std::string> base{"overlay=false", "window=3", "line_width=1.2"};
    auto with = [&](const std::string& more) {
        std::vector<std::string> s = base;
        s.push_back(more);
        return s;
    };
    const glm::ivec2 size{BUNDLE_W, BUNDLE_H};
    const Scene& scene = helix_bundle_scene();
    const Image ref = render_image(scene, "variant1_lineao", with("aa=false"), size, 4, "final", false, 6.0);
    const Image hard = render_image(scene, "variant1_lineao", with("aa=false"), size, 1, "final", false, 6.0);
    const Image soft = render_image(scene, "variant1_lineao", base, size, 1, "final", false, 6.0);
    const AaFigures h = aa_figures(hard, ref), s = aa_figures(soft, ref);
    if (const char* dir = std::getenv("PATHLET_PICTURE_DUMP")) {  // for looking at the images
        write_image(std::string(dir) + "/helix_ref.png", ref);
        write_image(std::string(dir) + "/helix_hard.png", hard);
        write_image(std::string(dir) + "/helix_soft.png", soft);
    }
    std::printf("helix bundle: RMS vs 4x4 supersampled: hard edges %.1f, edge_aa %.1f; speckles %.4f -> %.4f\n", h.rms,
                s.rms, h.speckle, s.speckle);
    EXPECT_LE(s.rms, 0.75 * h.rms);
    EXPECT_LE(s.speckle, 0.003);
    // LineAO's look stays: the bundle (left half) is darker than the isolated line (right).
    const Image lineao_off = render_image(scene, "variant1_lineao", with("strength=0"), size, 1, "final", false, 6.0);
    double with_ao = 0, without = 0;
    size_t n = 0;
    for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x / 2; ++x) {
            const float l = lineao_off.at(x, y, 0) + lineao_off.at(x, y, 1) + lineao_off.at(x, y, 2);
            if (l > 2.9f) continue;  // background
            ++n;
            without += l;
            with_ao += soft.at(x, y, 0) + soft.at(x, y, 1) + soft.at(x, y, 2);
        }
    ASSERT_GT(n, 500u);
    EXPECT_LT(with_ao / double(n), 0.9 * without / double(n)) << "LineAO must still darken the bundle";
}

// Halos: the G-buffer colour across a horizontal line, with and without halo, at widths from
// 1 to 20 px. The darkening summed across the line is what a 4x4 supersampled render of the same
// line draws (the band a share of the width at every size, its tint averaged over each pixel):
// present at every width, no bolder at small sizes (no darkening of thin lines), and no pixel
// turned into a black dot.
double halo_darkening(float px, int ssaa, double* deepest) {
    const int height = 120;
    const float ppu = square_on_pixels_per_unit(height);
    const float row = 0.5f * float(height) + 2.0f * ppu;  // the fast line at y = 0, rows top-down
    const std::string w = "line_width=" + std::to_string(px / ppu);
    // The reference's band is the width's share alone (halo_min_px 0 whatever the default).
    std::vector<std::string> sets{w, "window=0"};
    if (ssaa > 1) sets.push_back("gbuffer.halo_min_px=0");
    const Image on = render_image(two_speed_lines_scene(), "gbuffer_only", sets, {160, height}, ssaa, "color");
    const Image off = render_image(two_speed_lines_scene(), "gbuffer_only", {w, "window=0", "halo=0"}, {160, height}, ssaa,
                                   "color");
    double darkening = 0.0;
    *deepest = 0.0;
    for (int y = int(row - px) - 2; y <= int(row + px) + 2; ++y) {
        if (off.at(80, y, 3) == 0.0f) continue;
        const double l_on = on.at(80, y, 0) + on.at(80, y, 1) + on.at(80, y, 2);
        const double l_off = off.at(80, y, 0) + off.at(80, y, 1) + off.at(80, y, 2);
        const double d = 1.0 - l_on / std::max(l_off, 1e-6);
        // Weighted by the pixel's coverage: a supersampled pixel's colour is the mean of its
        // covered samples (box_downsample weighs colour by alpha), so its share of the line counts.
        darkening += off.at(80, y, 3) * d;
        *deepest = std::max(*deepest, d);
    }
    return darkening;
}

TEST(Halo, DarkensAsASupersampledRenderAtEveryWidth) {
    for (float px : {1.0f, 2.0f, 3.0f, 4.0f, 6.0f, 10.0f, 20.0f}) {
        SCOPED_TRACE("line width " + std::to_string(px) + " px");
        double deepest = 0.0, deepest_ref = 0.0;
        const double d = halo_darkening(px, 1, &deepest), ref = halo_darkening(px, 4, &deepest_ref);
        std::printf("halo, line %4.1f px wide: darkening %.3f, 4x4 supersampled %.3f\n", px, d, ref);
        EXPECT_GT(d, 0.05 * px) << "halo missing";
        EXPECT_NEAR(d, ref, 0.1 * ref + 0.05) << "the halo is not the supersampled render's";
        EXPECT_LT(deepest, 0.95) << "a pixel turned black: the band is not filtered";
    }
}

TEST(Overlay, GoldenWithTimeAndLegend) {
    const Image img = render_image(two_speed_lines_scene(), "variant1_lineao", {"window=3"}, {320, 180});
    EXPECT_TRUE(matches_golden(img, kHere + "/goldens/overlay.png"));
    // The legend's bar right of the data (the lines run on to the right edge after t = 5 s,
    // so it stands there): the colour map from slow (green, bottom) to fast (red, top).
    int x = 0;
    for (int cx = 319; cx > 160 && !x; --cx)
        if (img.at(cx, 90, 0) + img.at(cx, 90, 1) + img.at(cx, 90, 2) < 2.5f && img.at(cx, 90, 1) > 0.4f) x = cx;
    ASSERT_GT(x, 0) << "no colour bar right of the data";
    int top = 90, bottom = 90;
    while (top > 0 && img.at(x, top - 1, 0) + img.at(x, top - 1, 1) > 0.5f && img.at(x, top - 1, 2) < 0.5f) --top;
    while (bottom < 179 && img.at(x, bottom + 1, 0) + img.at(x, bottom + 1, 1) > 0.5f && img.at(x, bottom + 1, 2) < 0.5f)
        ++bottom;
    EXPECT_GT(bottom - top, 40) << "bar too short";
    EXPECT_GT(img.at(x, top + 1, 0), img.at(x, top + 1, 1)) << "fast end is red";
    EXPECT_GT(img.at(x, bottom - 1, 1), img.at(x, bottom - 1, 0)) << "slow end is green";
}

// Where two overlay frames differ: in the time label box (top left), the legend's title box
// (right, above the bar's middle) and anywhere else.
struct OverlayDiff {
    size_t label = 0, title = 0, elsewhere = 0;
};
OverlayDiff overlay_diff(const Image& a, const Image& b) {
    OverlayDiff d;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            bool diff = false;
            for (int c = 0; c < 4; ++c) diff |= a.at(x, y, c) != b.at(x, y, c);
            if (!diff) continue;
            (x < 100 && y < 30 ? d.label : x >= 200 && y < 75 ? d.title : d.elsewhere) += 1;
        }
    return d;
}

TEST(Overlay, UnitsComeFromTheDataAndNoneIsInvented) {
    const Scene& mm = two_speed_lines_scene();  // mm, s, mm/s
    Scene none = mm, metres = mm;
    none.lines.units = {};
    metres.lines.units = {"m", "s", "m/s"};
    auto shot = [](const Scene& s, std::vector<std::string> sets = {}) {
        sets.push_back("window=3");
        return render_image(s, "variant1_lineao", sets, {320, 180});
    };
    const Image a = shot(mm);
    // No units known: "speed" without one and "t = 5.00" without "s"; nothing else moves.
    OverlayDiff d = overlay_diff(a, shot(none));
    EXPECT_GT(d.label, 10u) << "the time label must lose its unit";
    EXPECT_GT(d.title, 10u) << "the legend's title must lose its unit";
    EXPECT_EQ(d.elsewhere, 0u);
    // Another velocity unit changes the title only.
    d = overlay_diff(a, shot(metres));
    EXPECT_EQ(d.label, 0u);
    EXPECT_GT(d.title, 10u);
    EXPECT_EQ(d.elsewhere, 0u);
    // The user's unit where the data has none: the title of a data set that says mm/s.
    d = overlay_diff(a, shot(none, {"overlay.speed_unit=mm/s"}));
    EXPECT_EQ(d.title, 0u);
    EXPECT_GT(d.label, 10u);
}

TEST(Overlay, StreamlinesShowNoTimeOrSpeedAndDirectionShowsItsKey) {
    Scene tracts = two_speed_lines_scene();
    tracts.lines.timeless = true;
    auto shot = [&](std::vector<std::string> sets) { return render_image(tracts, "variant1_lineao", sets, {320, 180}); };
    // Timeless lines: the overlay adds nothing (no clock, no speed).
    EXPECT_EQ(max_abs_difference(shot({}), shot({"overlay=false"})), 0.0f);
    // The direction colour map: an x/y/z key of pure red, green and blue swatches at the right.
    tracts.lines.timeless = false;  // the key is shown for timed lines too
    const Image key = render_image(tracts, "tracts_lineao", {}, {320, 180});  // direction by default
    const Image bare = render_image(tracts, "tracts_lineao", {"overlay.legend=false"}, {320, 180});
    auto is_pure = [](const Image& im, int x, int y, int c) {
        return im.at(x, y, c) > 0.99f && im.at(x, y, (c + 1) % 3) < 0.01f && im.at(x, y, (c + 2) % 3) < 0.01f;
    };
    int pure[3] = {0, 0, 0};
    for (int y = 0; y < key.height; ++y)
        for (int x = 0; x < key.width; ++x)
            for (int c = 0; c < 3; ++c) pure[c] += is_pure(key, x, y, c) && !is_pure(bare, x, y, c);
    for (int c = 0; c < 3; ++c) EXPECT_GT(pure[c], 20) << "swatch " << "xyz"[c];
}

TEST(Direction, ALineTakesTheColourOfItsAxes) {
    // Lines along x, along y and at 45 degrees in xy; the G-buffer colour at each line's centre
    // is |tangent| in data axes: red, green, and both at 0.707.
    Scene s;
    const glm::vec3 dirs[3] = {{1, 0, 0}, {0, 1, 0}, {0.70710678f, 0.70710678f, 0}};
    const glm::vec3 at[3] = {{5, 7, 0}, {-3, 2, 0}, {11, -3, 0}};
    for (int i = 0; i < 3; ++i) {
        LineRange r{uint32_t(s.lines.position.size()), 21};
        for (int k = 0; k <= 20; ++k) {
            s.lines.position.push_back(at[i] + (float(k) / 20.0f - 0.5f) * 6.0f * dirs[i]);
            s.lines.velocity.push_back(dirs[i]);
            s.lines.time.push_back(float(k));
        }
        s.lines.lines.push_back(r);
    }
    // The default framing looks along z with x up (the box's longest axis): view axes are not
    // the data's, so a colour from the view-space tangent would swap red and green.
    const Image c = render_image(s, "gbuffer_only", {"window=0", "gbuffer.colormap=direction", "line_width=0.6"}, {320, 180},
                                 1, "color", /*square_on=*/false);
    const Camera cam = frame_bounds(s.bounds(), {320, 180});
    auto px = [&](glm::vec3 p) {
        const glm::vec4 q = cam.proj * cam.view * glm::vec4(p, 1.0f);
        return glm::ivec2(std::lround((0.5f + 0.5f * q.x / q.w) * 320 - 0.5f), std::lround((0.5f - 0.5f * q.y / q.w) * 180 - 0.5f));
    };
    const glm::vec3 want[3] = {{1, 0, 0}, {0, 1, 0}, {0.7071f, 0.7071f, 0}};
    for (int i = 0; i < 3; ++i) {
        const glm::ivec2 p = px(at[i]);
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(c.at(p.x, p.y, ch), want[i][ch], 0.02f) << "line " << i << " channel " << ch;
    }
}

TEST(Overlay, TimeLabelFollowsTheClockAndNothingElseMoves) {
    auto frame = [](double t) {
        return render_image(two_speed_lines_scene(), "variant1_lineao", {"window=0"}, {320, 180}, 1, "final", true, t);
    };
    const Image a = frame(2.0), b = frame(7.0);
    size_t label = 0, elsewhere = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            bool diff = false;
            for (int c = 0; c < 4; ++c) diff |= a.at(x, y, c) != b.at(x, y, c);
            (x < 100 && y < 30 ? label : elsewhere) += diff;
        }
    EXPECT_GT(label, 10u) << "t = 2.00 s and t = 7.00 s must differ in the label";
    EXPECT_EQ(elsewhere, 0u) << "whole lines (window 0): only the label changes";
}

// A supersampled render carries the overlay of the plain one: the annotation is laid out and
// rasterised for the output picture, not drawn N times larger (its glyphs, filtered down, were
// a stroke's width off the font's own small raster: RMS 140 over the time label at 1280x720).
TEST(Overlay, SupersampledRenderHasThePlainRendersOverlay) {
    auto frame = [](int ssaa, const std::string& overlay) {
        return render_image(two_speed_lines_scene(), "variant1_lineao", {"window=0", "aa=false", overlay}, {320, 180},
                            ssaa);
    };
    const Image plain = frame(1, "overlay=true"), super = frame(4, "overlay=true");
    const Image plain_bare = frame(1, "overlay=false"), super_bare = frame(4, "overlay=false");
    size_t ink = 0;
    float worst = 0.0f;
    for (int y = 0; y < plain.height; ++y)
        for (int x = 0; x < plain.width; ++x) {
            bool empty = true, inked = false;  // no line in either render; the overlay drew here
            for (int c = 0; c < 3; ++c) {
                empty &= plain_bare.at(x, y, c) == 1.0f && super_bare.at(x, y, c) == 1.0f;
                inked |= plain.at(x, y, c) < 1.0f;
            }
            if (!empty || !inked) continue;
            ++ink;
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(plain.at(x, y, c) - super.at(x, y, c)));
        }
    EXPECT_GT(ink, 300u) << "the time label and the legend must be there";
    EXPECT_LE(worst, 2.0f / 255.0f) << "the supersampled overlay is not the plain render's";
}

// A render's picture and what it printed on stderr (the overlay's font warnings).
std::pair<Image, std::string> render_with_stderr(const std::vector<std::string>& sets) {
    testing::internal::CaptureStderr();
    Image img;
    try {
        img = render_image(two_speed_lines_scene(), "variant1_lineao", sets, {320, 180});
    } catch (...) {
        testing::internal::GetCapturedStderr();
        throw;
    }
    return {img, testing::internal::GetCapturedStderr()};
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// Labels never cost the picture: a font file that is not there gives one warning
// saying "not found" and the built-in font; the lines are the picture without an overlay.
TEST(Overlay, MissingFontWarnsOnceAndKeepsThePicture) {
    const std::string font = scratch("no_such_folder") + "/DejaVuSans.ttf";  // the user's overlay.font
    const auto [img, err] = render_with_stderr({"window=3", "overlay.font=" + font});
    const std::string warning = "warning: overlay: font '" + font + "' not found; the labels use the built-in font";
    EXPECT_EQ(count(err, warning), 1u) << err;
    EXPECT_EQ(count(err, "warning"), 1u) << err;
    const auto [again, err2] = render_with_stderr({"window=3", "overlay.font=" + font});  // setup once more
    EXPECT_EQ(count(err2, "warning"), 0u) << "one warning per font, not one per setup: " << err2;
    EXPECT_EQ(overlay_diff(img, again).label + overlay_diff(img, again).elsewhere, 0u);

    const Image bare = render_image(two_speed_lines_scene(), "variant1_lineao", {"window=3", "overlay=false"}, {320, 180});
    const Image dejavu = render_image(two_speed_lines_scene(), "variant1_lineao", {"window=3"}, {320, 180});
    size_t lines = 0, outside = 0, label = 0, label_vs_dejavu = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            bool diff = false, font_diff = false;
            for (int c = 0; c < 4; ++c) {
                diff |= img.at(x, y, c) != bare.at(x, y, c);
                font_diff |= img.at(x, y, c) != dejavu.at(x, y, c);
            }
            const bool time_label = x < 100 && y < 30, legend = x >= 200;
            lines += bare.at(x, y, 0) + bare.at(x, y, 1) + bare.at(x, y, 2) < 2.4f;
            outside += diff && !time_label && !legend;
            label += diff && time_label;
            label_vs_dejavu += font_diff && time_label;
        }
    EXPECT_GT(lines, 150u) << "the scene's lines are drawn";
    EXPECT_EQ(outside, 0u) << "outside the labels the picture is the one without an overlay";
    EXPECT_GT(label, 30u) << "the time label is drawn in the built-in font";
    EXPECT_GT(label_vs_dejavu, 30u) << "and not in DejaVu Sans";
}

// The default font is the share folder's (a bundle carries it): a broken one there is what the
// overlay opens and names, rather than another font found elsewhere.
TEST(Overlay, DefaultFontComesFromTheShareFolder) {
    namespace fs = std::filesystem;
    const fs::path share = scratch("share");
    fs::remove_all(share);
    fs::create_directories(share / "fonts");
    const fs::path built = fs::path(PATHLET_BUILD_DIR) / "share" / "pathlet";
    ASSERT_TRUE(fs::exists(built / "fonts" / "DejaVuSans.ttf")) << "the build's share folder carries the label font";
    ASSERT_TRUE(fs::exists(built / "fonts" / "LICENSE-DejaVu.txt")) << "with its licence";
    fs::create_directory_symlink(built / "shaders", share / "shaders");
    fs::create_directory_symlink(built / "graphs", share / "graphs");
    std::ofstream(share / "fonts" / "DejaVuSans.ttf") << "not a font";
    setenv("PATHLET_SHARE_DIR", share.c_str(), 1);
    const auto result = [] {
        try {
            return render_with_stderr({"window=3"});
        } catch (...) {
            unsetenv("PATHLET_SHARE_DIR");
            throw;
        }
    }();
    unsetenv("PATHLET_SHARE_DIR");
    const std::string& err = result.second;
    EXPECT_EQ(count(err, "warning: overlay: font '" + (share / "fonts" / "DejaVuSans.ttf").string() +
                             "' refused: its content is not a TrueType/OpenType font"),
              1u)
        << err;
    fs::remove_all(share);
}

// overlay.font comes from a graph: only a regular .ttf/.otf/.ttc file that starts like a font
// is opened; anything else is refused with what is allowed, before FreeType sees it, and the
// labels use the built-in font.
TEST(Overlay, FontParameterOpensOnlyFontFiles) {
    const std::filesystem::path dir = std::filesystem::path(PATHLET_TEST_BINARY_DIR) / "font_checks";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir / "folder.ttf");
    std::filesystem::copy_file("/etc/passwd", dir / "passwd.ttf");
    for (const auto& [font, why] : std::vector<std::pair<std::string, std::string>>{
             {"/etc/passwd", "refused: not a font file name"},
             {(dir / "passwd.ttf").string(), "refused: its content is not a TrueType/OpenType font"},
             {(dir / "folder.ttf").string(), "refused: not a regular file"}}) {
        const auto [img, err] = render_with_stderr({"overlay.font=" + font});
        EXPECT_EQ(count(err, "warning: overlay: font '" + font + "' " + why), 1u) << err;
        EXPECT_NE(err.find("allowed: regular TrueType/OpenType files named .ttf, .otf or .ttc"), std::string::npos) << err;
        EXPECT_EQ(img.width, 320) << "the picture is there";
    }
    std::filesystem::remove_all(dir);
}

TEST(Ssaa, BoxDownsampleWeighsColourByAlpha) {
    Image img;
    img.width = 2;
    img.height = 2;
    img.pixels = {1, 0, 0, 1, /**/ 0, 0, 1, 0, /**/ 1, 0, 0, 1, /**/ 0, 0, 1, 0};  // red opaque, blue transparent
    const Image d = box_downsample(img, 2);
    ASSERT_EQ(d.width, 1);
    EXPECT_FLOAT_EQ(d.at(0, 0, 0), 1.0f) << "transparent blue adds no colour";
    EXPECT_FLOAT_EQ(d.at(0, 0, 2), 0.0f);
    EXPECT_FLOAT_EQ(d.at(0, 0, 3), 0.5f);
}

TEST(Ssaa, RenderWritesTheRequestedSizeAndLooksLikeTheFrame) {
    RenderOptions opt;
    opt.graph_path = kSrc + "/graphs/variant1_lineao.json";
    opt.sets = {"window=3", "line_width=1.2", "overlay=false"};
    opt.size = {80, 60};
    opt.time.start = 6.0;
    opt.ssaa = 3;
    opt.out_dir = scratch("ssaa");
    opt.quiet = true;
    opt.warmup = 0;
    RenderResult r = render(test_runtime(), helix_bundle_scene(), opt);
    ASSERT_EQ(r.files.size(), 1u);
    const Image img = read_image(r.files[0]);
    EXPECT_EQ(img.width, 80);
    EXPECT_EQ(img.height, 60);
    opt.ssaa = 1;
    opt.out_dir = scratch("plain");
    const Image plain = read_image(render(test_runtime(), helix_bundle_scene(), opt).files[0]);
    // Same framing and look: close on average, but not the same pixels.
    const double d = std::fabs(mean_luminance(img) - mean_luminance(plain));
    EXPECT_LT(d, 0.03);
    EXPECT_NE(img.pixels, plain.pixels);
}
