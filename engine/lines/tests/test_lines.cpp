// The line passes on real GL (llvmpipe): goldens of graphs/isl.json and graphs/gbuffer_only.json
// at 160x120, and the G-buffer contract with lineao (background values, unit normals, linear
// depth in [0,1], zoom), the time window, halos, determinism and shader errors. The suite is
// `lines` (lower case) so that `ctest -R lines` selects it.
#include "camera.hpp"
#include "executor.hpp"
#include "frame_capture.hpp"
#include "golden.hpp"
#include "image_io.hpp"
#include "image_probes.hpp"
#include "renderer.hpp"
#include "runtime.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <pathlet/gpu_scene.hpp>
#include <pathlet/lines.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <unistd.h>

namespace fs = std::filesystem;
using namespace pathlet;

namespace {

const glm::ivec2 kSize{160, 120};
const std::string kGraphs = std::string(PATHLET_SOURCE_DIR) + "/graphs/";
const std::string kGoldens = std::string(PATHLET_TEST_SOURCE_DIR) + "/goldens/";

// The shared test bundle (tests/support/frame_capture.hpp): 40 helices and an isolated line.
const Scene& test_scene() { return helix_bundle_scene(); }

Runtime& runtime() { return test_runtime(); }

Frame render_frame(const std::string& graph, double t, std::vector<std::string> sets, std::vector<std::string> names,
                   const Scene& scene = test_scene(), glm::ivec2 size = kSize) {
    RenderOptions opt;
    opt.graph_path = kGraphs + graph;
    opt.sets = std::move(sets);
    opt.size = size;
    opt.time.start = t;
    return pathlet::render_frame(runtime(), scene, opt, names);
}

const std::vector<std::string> kGbuf{"color", "normal_depth", "zoom", "depth"};

Frame gbuffer(double t, std::vector<std::string> sets = {}) {
    sets.insert(sets.begin(), "line_width=1.2");
    return render_frame("gbuffer_only.json", t, sets, kGbuf);
}

bool covered(const Image& color, int x, int y) { return color.at(x, y, 3) > 0.5f; }

size_t coverage(const Image& color) {
    size_t n = 0;
    for (int y = 0; y < color.height; ++y)
        for (int x = 0; x < color.width; ++x) n += covered(color, x, y);
    return n;
}

}  // namespace

TEST(lines, GoldenIsl) {
    Frame f = render_frame("isl.json", 6.0, {"line_width=1.2", "window=3", "overlay=false"}, {"final"});
    EXPECT_TRUE(matches_golden(f["final"], kGoldens + "isl.png"));
}

TEST(lines, GoldenGbufferColor) {
    Frame f = gbuffer(6.0, {"window=3"});
    EXPECT_TRUE(matches_golden(f["color"], kGoldens + "gbuffer_only.png"));
}

TEST(lines, GbufferBackgroundIsExactlyTheContract) {
    Frame f = gbuffer(5.0, {"gbuffer.background=#336699"});
    const Image &c = f["color"], &nd = f["normal_depth"], &z = f["zoom"], &d = f["depth"];
    size_t bg = 0;
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) {
            if (covered(c, x, y)) {
                EXPECT_EQ(c.at(x, y, 3), 1.0f);
                continue;
            }
            ++bg;
            ASSERT_EQ(to_unorm8(c.at(x, y, 0)), 0x33) << x << "," << y;
            ASSERT_EQ(to_unorm8(c.at(x, y, 1)), 0x66);
            ASSERT_EQ(to_unorm8(c.at(x, y, 2)), 0x99);
            ASSERT_EQ(c.at(x, y, 3), 0.0f);
            for (int k = 0; k < 3; ++k) ASSERT_EQ(nd.at(x, y, k), 0.0f);
            ASSERT_EQ(nd.at(x, y, 3), 1.0f);
            ASSERT_EQ(z.at(x, y, 0), 0.0f);
            ASSERT_EQ(d.at(x, y, 0), 1.0f);
        }
    EXPECT_GT(bg, size_t(c.width * c.height / 2));
    EXPECT_GT(coverage(c), 200u);
}

TEST(lines, IslBackgroundIsExactlyTheBackgroundColour) {
    Frame f = render_frame("isl.json", 5.0, {"line_width=1.2", "isl.background=#336699"}, {"lit", "depth"});
    const Image &c = f["lit"], &d = f["depth"];
    size_t bg = 0, lines = 0;
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) {
            EXPECT_EQ(c.at(x, y, 3), 1.0f);
            if (d.at(x, y, 0) < 1.0f) {
                ++lines;
                continue;
            }
            ++bg;
            ASSERT_EQ(to_unorm8(c.at(x, y, 0)), 0x33) << x << "," << y;
            ASSERT_EQ(to_unorm8(c.at(x, y, 1)), 0x66);
            ASSERT_EQ(to_unorm8(c.at(x, y, 2)), 0x99);
        }
    EXPECT_GT(bg, 0u);
    EXPECT_GT(lines, 200u);
}

TEST(lines, GbufferValuesAreFiniteUnitAndInRange) {
    Frame f = gbuffer(5.0, {"window=0"});
    const Image &c = f["color"], &nd = f["normal_depth"], &z = f["zoom"];
    EXPECT_FALSE(has_nan(nd));
    EXPECT_FALSE(has_nan(z));
    size_t n = 0;
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) {
            float w = nd.at(x, y, 3);
            ASSERT_GE(w, 0.0f);
            ASSERT_LE(w, 1.0f);
            ASSERT_TRUE(std::isfinite(z.at(x, y, 0)));
            if (!covered(c, x, y)) continue;
            ++n;
            glm::vec3 v(nd.at(x, y, 0), nd.at(x, y, 1), nd.at(x, y, 2));
            ASSERT_NEAR(glm::length(v), 1.0f, 0.01f) << x << "," << y;
            ASSERT_GT(v.z, -0.2f) << "tube normals face the viewer";
            ASSERT_LT(w, 1.0f);
            ASSERT_GT(z.at(x, y, 0), 0.0f);
        }
    EXPECT_GT(n, 500u);
}

TEST(lines, ZoomIsPixelsPerWorldUnitAtALineCentre) {
    // A thin isolated line: the tube offset (<= r) stays well under 1 % of the distance.
    Frame f = render_frame("gbuffer_only.json", 5.0, {"window=0", "line_width=0.6", "halo=0"}, kGbuf);
    const Camera& cam = f.camera;
    const glm::vec3 p(20.0f, float(12 + 0.5 * std::sin(2.5)), 0.0f);  // isolated line at t = 5
    glm::vec4 eye = cam.view * glm::vec4(p, 1.0f);
    glm::vec4 clip = cam.proj * eye;
    int px = int(std::floor((clip.x / clip.w * 0.5f + 0.5f) * float(kSize.x)));
    int py = kSize.y - 1 - int(std::floor((clip.y / clip.w * 0.5f + 0.5f) * float(kSize.y)));
    // The pixel nearest the line's centre around the projection: the normal faces the viewer most.
    const Image &c = f["color"], &nd = f["normal_depth"], &z = f["zoom"];
    int bx = -1, by = -1;
    float best = -2.0f;
    for (int y = py - 1; y <= py + 1; ++y)
        for (int x = px - 1; x <= px + 1; ++x)
            if (x >= 0 && y >= 0 && x < kSize.x && y < kSize.y && covered(c, x, y) && nd.at(x, y, 2) > best) {
                best = nd.at(x, y, 2);
                bx = x;
                by = y;
            }
    ASSERT_GE(bx, 0) << "isolated line not found near pixel " << px << "," << py;
    double expected = 0.5 * kSize.y * cam.proj[1][1] / -eye.z;
    EXPECT_NEAR(z.at(bx, by, 0) / expected, 1.0, 0.01) << "zoom " << z.at(bx, by, 0) << " expected " << expected;
}

TEST(lines, TimeWindowDrawsFewerSegmentsAndMoves) {
    Frame whole = gbuffer(5.0, {"window=0"});
    Frame w3 = gbuffer(3.0, {"window=1"});
    Frame w6 = gbuffer(6.0, {"window=1"});
    EXPECT_EQ(whole.stats.at("segments_exact"), 41 * 100);  // before the level of detail
    EXPECT_LE(whole.stats.at("segments"), 41 * 100);
    EXPECT_EQ(whole.stats.at("lines"), 41);
    EXPECT_GT(w3.stats.at("segments"), 0);
    EXPECT_LT(w3.stats.at("segments_exact"), whole.stats.at("segments_exact") / 4);
    size_t n3 = coverage(w3["color"]), n6 = coverage(w6["color"]), both = 0;
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) both += covered(w3["color"], x, y) && covered(w6["color"], x, y);
    EXPECT_GT(n3, 50u);
    EXPECT_GT(n6, 50u);
    EXPECT_LT(coverage(w3["color"]), coverage(whole["color"]));
    EXPECT_LT(both, n3 / 10) << "pathlets at t=3 and t=6 should cover different pixels";
}

TEST(lines, WindowClipsSmoothlyInsideASegment) {
    // The isolated line runs straight up the image at 4 mm/s; data points are 0.4 mm apart.
    // Clipped in time, its pathlet spans exactly [4(t-1), 4t] at any t, not whole segments.
    const glm::ivec2 size{480, 360};
    for (double t : {5.0, 5.03, 5.06}) {
        Frame f = render_frame("gbuffer_only.json", t, {"window=1", "line_width=1.2"},
                               {"line_id"}, test_scene(), size);
        const Image& id = f["line_id"];
        int top = size.y, bottom = -1;
        for (int y = 0; y < size.y; ++y)
            for (int x = 0; x < size.x; ++x)
                if (id.at(x, y, 0) == 40.0f) {
                    top = std::min(top, y);
                    bottom = std::max(bottom, y);
                }
        auto row_of = [&](double tp) {  // image row (top first, continuous) of the line at time tp
            glm::vec4 c = f.camera.proj * f.camera.view * glm::vec4(4 * tp, 12 + 0.5 * std::sin(0.5 * tp), 0, 1);
            return double(size.y) * (1.0 - (c.y / c.w * 0.5 + 0.5));
        };
        // Head (larger x) is up: the top covered row holds the head, the bottom one the tail.
        EXPECT_NEAR(top + 0.5, row_of(t), 1.5) << "head at t=" << t;
        EXPECT_NEAR(bottom + 0.5, row_of(t - 1.0), 1.5) << "tail at t=" << t;
    }
}

TEST(lines, Deterministic) {
    Frame a = gbuffer(5.0), b = gbuffer(5.0);
    for (const auto& n : kGbuf) EXPECT_EQ(a[n].pixels, b[n].pixels) << n;
    Frame ia = render_frame("isl.json", 5.0, {}, {"final"}), ib = render_frame("isl.json", 5.0, {}, {"final"});
    EXPECT_EQ(ia["final"].pixels, ib["final"].pixels);
}

TEST(lines, HalosDarkenRimsAndArePushedBack) {
    std::vector<std::string> common{"window=0", "line_width=2", "gbuffer.halo_depth=0.05"};
    auto with = [&](const char* halo) {
        auto s = common;
        s.push_back(halo);
        return gbuffer(5.0, s);
    };
    Frame on = with("halo=0.4"), off = with("halo=0");
    const Image &con = on["color"], &coff = off["color"];
    size_t changed = 0, pushed = 0;
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) {
            // Same quads either way: the halo lives inside the width.
            ASSERT_EQ(covered(con, x, y), covered(coff, x, y)) << x << "," << y;
            if (!covered(con, x, y)) continue;
            float lum_on = con.at(x, y, 0) + con.at(x, y, 1) + con.at(x, y, 2);
            float lum_off = coff.at(x, y, 0) + coff.at(x, y, 1) + coff.at(x, y, 2);
            float d_on = on["normal_depth"].at(x, y, 3), d_off = off["normal_depth"].at(x, y, 3);
            EXPECT_GE(d_on, d_off - 1e-3f) << "a halo never pulls depth forward";
            if (lum_on < lum_off - 0.05f) {
                ++changed;
                pushed += d_on > d_off + 1e-3f;
            }
        }
    EXPECT_GT(changed, 100u);
    EXPECT_GT(pushed, changed / 2) << "darkened rim pixels lie behind the halo-free ones";
}

TEST(lines, LineIdOutput) {
    Frame f = render_frame("gbuffer_only.json", 5.0, {"line_width=1.2"},
                           {"color", "line_id"});
    const Image &c = f["color"], &id = f["line_id"];
    bool saw_isolated = false;
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) {
            float v = id.at(x, y, 0);
            if (!covered(c, x, y)) {
                ASSERT_EQ(v, -1.0f);
            } else {
                ASSERT_GE(v, 0.0f);
                ASSERT_LE(v, 40.0f);
                saw_isolated |= v == 40.0f;
            }
        }
    EXPECT_TRUE(saw_isolated);
}

TEST(lines, EmptySceneJustClears) {
    Scene empty;
    Frame f = render_frame("gbuffer_only.json", 0.0, {}, kGbuf, empty);
    EXPECT_EQ(coverage(f["color"]), 0u);
    EXPECT_EQ(f.stats.at("segments"), 0);
    EXPECT_EQ(f["normal_depth"].at(3, 3, 3), 1.0f);
}

namespace {
// Copies `file` from `from` into `dir` with line `needle`'s line replaced by `broken`;
// returns that line's number.
int copy_broken(const fs::path& from, const fs::path& dir, const std::string& needle, const std::string& broken) {
    std::ifstream in(from);
    std::ostringstream out;
    std::string line;
    int n = 0, hit = 0;
    while (std::getline(in, line)) {
        ++n;
        if (!hit && line.find(needle) != std::string::npos) {
            hit = n;
            line = broken;
        }
        out << line << "\n";
    }
    std::ofstream(dir / from.filename()) << out.str();
    return hit;
}

struct ShaderPathGuard {
    explicit ShaderPathGuard(const std::string& dir) { setenv("PATHLET_SHADER_PATH", dir.c_str(), 1); }
    ~ShaderPathGuard() { unsetenv("PATHLET_SHADER_PATH"); }
};

std::string render_error(const std::string& graph) {
    try {
        render_frame(graph, 5.0, {}, {});
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(lines, BrokenShaderNamesFileAndLine) {
    fs::path dir = fs::temp_directory_path() / ("pathlet_lines_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path src = PATHLET_SOURCE_DIR;
    {
        int line = copy_broken(src / "engine/lines/shaders/line_gbuffer.frag", dir, "LineFrag f = line_fragment();",
                               "    LineFrag f = line_fragment() +;");
        ASSERT_GT(line, 0);
        ShaderPathGuard guard(dir.string());
        std::string msg = render_error("gbuffer_only.json");
        EXPECT_NE(msg.find("GLSL compile error"), std::string::npos) << msg;
        EXPECT_NE(msg.find((dir / "line_gbuffer.frag").string() + ":" + std::to_string(line) + ":"), std::string::npos)
            << msg;
        fs::remove(dir / "line_gbuffer.frag");
    }
    {
        // A shared include: the message names the included file, not the stage file.
        int line = copy_broken(src / "engine/lines/shaders/line_common.glsl", dir, "float c = sqrt(", "    float c = sqrt(;");
        ASSERT_GT(line, 0);
        ShaderPathGuard guard(dir.string());
        std::string msg = render_error("isl.json");
        EXPECT_NE(msg.find((dir / "line_common.glsl").string() + ":" + std::to_string(line) + ":"), std::string::npos)
            << msg;
    }
    {
        // The LineKit uniform block out of step with lines::Drawer's struct: named, never drawn.
        // Every kit stage and hook must see the edited block: the whole kit folder on the path.
        for (const auto& e : fs::directory_iterator(src / "engine/lines/shaders"))
            fs::copy_file(e.path(), dir / e.path().filename(), fs::copy_options::overwrite_existing);
        int line = copy_broken(src / "engine/lines/shaders/line_kit_block.glsl", dir, "vec2 u_depth_range;",
                               "    float u_inserted; vec2 u_depth_range;");
        ASSERT_GT(line, 0);
        ShaderPathGuard guard(dir.string());
        std::string msg = render_error("isl.json");
        EXPECT_NE(msg.find("member u_depth_range of the LineKit block is at offset 144 in GLSL but 136"),
                  std::string::npos)
            << msg;
    }
    fs::remove_all(dir);
}

// The level of detail (gbuffer.lod, pathlet/line_lod.hpp) draws far fewer segments at 4x the
// size of the golden and leaves the picture what it was: the same pixels covered but for an
// edge pixel flipping here and there, and the same colours but where two crossing lines at
// nearly equal depth swap a pixel. lod=0 draws every segment.
TEST(lines, LevelOfDetailDrawsFewerSegmentsAndKeepsThePicture) {
    const glm::ivec2 size = 4 * kSize;
    // Without halos: the aliased 1-pixel halo rims flip wherever an edge moves by a fraction of
    // a pixel, which says nothing about the lines (their share is checked below).
    auto frame = [&](const std::string& lod, const std::string& halo) {
        return render_frame("gbuffer_only.json", 5.0,
                            {"line_width=1.2", "window=0", "gbuffer.lod=" + lod, "gbuffer.halo=" + halo}, kGbuf,
                            test_scene(), size);
    };
    Frame exact = frame("0", "0"), lod = frame("0.25", "0");
    EXPECT_EQ(exact.stats.at("segments"), exact.stats.at("segments_exact"));
    EXPECT_LT(lod.stats.at("segments"), 0.7 * lod.stats.at("segments_exact"));
    EXPECT_EQ(lod.stats.at("segments_exact"), exact.stats.at("segments_exact"));
    const Image &a = exact["color"], &b = lod["color"];
    size_t covered_a = 0, flips = 0;
    double sq = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            bool ca = covered(a, x, y), cb = covered(b, x, y);
            covered_a += ca;
            flips += ca != cb;
            if (ca && cb)  // colour where both are covered; coverage changes are the flips
                for (int c = 0; c < 3; ++c) sq += std::pow(255.0 * (a.at(x, y, c) - b.at(x, y, c)), 2);
        }
    ASSERT_GT(covered_a, 1000u);
    EXPECT_LT(double(flips), 0.01 * double(covered_a)) << flips << " of " << covered_a << " pixels changed coverage";
    const double rms = std::sqrt(sq / (3.0 * double(covered_a)));
    // Measured 4.6: isolated depth-order flips where helices cross at nearly equal depth.
    EXPECT_LT(rms, 7.0) << "RMS over pixels covered in both, of 255";
    std::printf("lod 0.25 px: %.0f of %.0f segments, RMS %.2f/255, %zu coverage flips of %zu\n",
                lod.stats.at("segments"), exact.stats.at("segments"), rms, flips, covered_a);
    // With halos: as many halo pixels (dark) as before, to a few per cent.
    auto dark = [](const Image& c) {
        size_t n = 0;
        for (int y = 0; y < c.height; ++y)
            for (int x = 0; x < c.width; ++x) n += c.at(x, y, 3) > 0.5f && c.at(x, y, 0) + c.at(x, y, 1) < 0.5f;
        return double(n);
    };
    const double halo_exact = dark(frame("0", "0.2")["color"]), halo_lod = dark(frame("0.25", "0.2")["color"]);
    ASSERT_GT(halo_exact, 500.0);
    EXPECT_NEAR(halo_lod / halo_exact, 1.0, 0.05) << halo_lod << " dark halo pixels, exact " << halo_exact;
}

// Post passes (lineao, bilateral, gauss_pyramid, edge_aa) run only inside lines::screen_rect:
// it must hold every quad a line pass can draw, however wide the lines are set (the widest
// width drawn is noted by the kit) and however far a width hook widens them (clamped to 4x).
TEST(lines, ScreenRectHoldsTheWidestQuadAWidthHookCanDraw) {
    Scene scene;
    scene.lines.lines.push_back({0, 2});
    for (float x : {-8.0f, 8.0f}) {  // one horizontal line: its box has no height
        scene.lines.position.push_back(glm::vec3(x, 0.0f, 0.0f));
        scene.lines.velocity.push_back(glm::vec3(1.0f, 0.0f, 0.0f));
        scene.lines.time.push_back(x + 8.0f);
    }
    GpuScene gpu;
    gpu.upload(scene);
    const glm::ivec2 size(320, 240);
    Camera cam;  // looking down -z at the line, which spans about two thirds of the width
    cam.view = glm::lookAt(glm::vec3(0.0f, 0.0f, 30.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    cam.proj = glm::perspective(glm::radians(40.0f), float(size.x) / float(size.y), 1.0f, 100.0f);
    const float width = 10.0f * gpu.auto_line_width();  // far beyond the auto-width padding
    // The widest quad: half width = width/2 * 4 (hook clamp); its top and bottom edge in pixels.
    auto pixel_y = [&](float y) {
        const glm::vec4 c = cam.proj * cam.view * glm::vec4(0.0f, y, 0.0f, 1.0f);
        return (c.y / c.w * 0.5f + 0.5f) * float(size.y);
    };
    const float half = 0.5f * width * GpuScene::kMaxWidthHook;
    const float top = pixel_y(half), bottom = pixel_y(-half);
    const glm::ivec4 before = lines::screen_rect(gpu, cam, size, 0);
    EXPECT_GT(float(before.y), bottom) << "the test line must be wider than the auto-width padding";
    gpu.note_line_width(width);
    const glm::ivec4 r = lines::screen_rect(gpu, cam, size, 0);
    EXPECT_LE(float(r.y), std::max(bottom, 0.0f));
    EXPECT_GE(float(r.w), std::min(top, float(size.y)));
    EXPECT_LT(r.w - r.y, size.y) << "a line far from the frame's edges still skips some rows: " << r.y << ".."
                                 << r.w << " for " << bottom << ".." << top;
}

// A level's rectangle rounds outwards: every texel with a child in the level-0 rectangle is in.
TEST(lines, RectAtLevelRoundsOutwards) {
    const glm::ivec4 r = lines::rect_at_level({5, 9, 11, 14}, 2, 0, {100, 100});
    EXPECT_EQ(r, glm::ivec4(1, 2, 3, 4));  // 5/4, 9/4 down; 11/4, 14/4 up
    EXPECT_EQ(lines::rect_at_level({0, 0, 7, 7}, 1, 1, {3, 3}), glm::ivec4(0, 0, 3, 3));  // clamped to the level
}

// isl compiles whole exponents in as products (shaders/pow_whole.glsl): the image must be what
// pow() draws (an exponent a hair off a whole number takes the pow path), for the specular and
// the diffuse exponent, and each must matter, or the comparison would prove nothing.
TEST(lines, IslWholeExponentsDrawWhatPowDraws) {
    auto render = [](const std::string& set) {
        return render_frame("isl.json", 5.0, {"line_width=1.2", "overlay=false", "aa=false", set}, {"final"})["final"];
    };
    for (const char* set : {"isl.exponent=50", "isl.exponent=9", "isl.diffuse_exponent=1", "isl.diffuse_exponent=3"}) {
        EXPECT_LE(max_abs_difference(render(set), render(std::string(set) + ".0001")), 1.5f / 255.0f) << set;
    }
    EXPECT_GT(max_abs_difference(render("isl.exponent=50"), render("isl.exponent=2")), 0.1f);
    EXPECT_GT(max_abs_difference(render("isl.diffuse_exponent=1"), render("isl.diffuse_exponent=3")), 0.1f);
}
