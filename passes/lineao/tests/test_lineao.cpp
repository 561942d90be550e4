// LineAO pipeline on a synthetic scene built here: a dense bundle of 40 helical lines and one
// isolated straight line far from it, all drawn whole (window <= 0). One golden image for
// variant1_lineao; everything else is checked as properties of the AO term.
#include "camera.hpp"
#include "executor.hpp"
#include "golden.hpp"
#include "image_io.hpp"
#include "image_probes.hpp"
#include "renderer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

using namespace pathlet;

namespace {

const glm::ivec2 kSize{160, 120};

std::string source(const std::string& rel) { return std::string(PATHLET_SOURCE_DIR) + "/" + rel; }

Runtime& runtime() {  // one per process: contexts are slow to create on llvmpipe
    static Runtime* rt = [] {
        auto* r = new Runtime();
        r->load_plugins({});
        r->ensure_gl(true);
        return r;
    }();
    return *rt;
}

// Lines run along x. Bundle: 40 helices (radii 0.15..0.75 around the x axis) -> dense,
// overlapping on screen. Isolated: one straight line at y = 4.5. The camera frames the box
// along its thinnest axis (z), so both are seen side on.
constexpr float kLength = 8.0f, kIsolatedY = 4.5f;
Scene test_scene() {
    Scene s;
    s.source = "lineao-test";
    auto add_line = [&](auto&& pos) {
        LineRange r{uint32_t(s.lines.position.size()), 0};
        for (int k = 0; k <= 64; ++k) {
            float x = kLength * float(k) / 64.0f;
            s.lines.position.push_back(pos(x));
            s.lines.time.push_back(float(k) / 64.0f);
            s.lines.velocity.push_back({1.0f + 0.02f * float(r.first % 7), 0.0f, 0.0f});
            ++r.count;
        }
        s.lines.lines.push_back(r);
    };
    for (int j = 0; j < 40; ++j) {
        const float rho = 0.15f + 0.6f * float(j % 5) / 4.0f;
        const float phase = 6.2831853f * float(j) / 40.0f * 7.0f;
        add_line([=](float x) {
            float a = phase + 0.6f * x;
            return glm::vec3(x, rho * std::cos(a), rho * std::sin(a));
        });
    }
    add_line([](float x) { return glm::vec3(x, kIsolatedY, 0.0f); });
    return s;
}

struct Frame {
    Image color, nd, ao, lit, final_img;
    Camera cam;
};

Frame render_frame(std::vector<std::string> sets = {}, const std::string& graph = "graphs/variant1_lineao.json") {
    // The overlay (its own golden in engine/lines/tests) would put text into every AO measurement.
    sets.insert(sets.begin(), {"window=0", "line_width=0.15", "overlay=false"});
    Scene scene = test_scene();
    RenderOptions o;
    o.graph_path = source(graph);
    o.size = kSize;
    o.sets = std::move(sets);
    o.warmup = 0;
    o.write_images = false;
    o.quiet = true;
    o.keep = {"color", "normal_depth", "ao", "lit", "final"};  // read after the frame: not pooled
    Frame f;
    render(runtime(), scene, o, [&](const Executor& e, size_t) {
        auto read = [&](const char* name, int channels) {
            Texture t = e.texture(name);
            return read_texture(t.id, t.width, t.height, 0, channels);
        };
        f.color = read("color", 4);
        f.nd = read("normal_depth", 4);
        f.ao = read("ao", 1);
        f.final_img = read("final", 4);
        f.lit = read("lit", 4);
    });
    f.cam = frame_bounds(scene.bounds(), kSize);
    if (const char* dir = std::getenv("PATHLET_LINEAO_DUMP")) {  // for looking at the images
        std::string tag;
        for (const auto& s : o.sets) tag += "_" + s;
        write_image(std::string(dir) + "/ao" + tag + ".png", f.ao);
        write_image(std::string(dir) + "/final" + tag + ".png", f.final_img);
        write_image(std::string(dir) + "/color" + tag + ".png", f.color);
    }
    return f;
}

bool geometry(const Frame& f, int x, int y) {
    float n2 = 0;
    for (int c = 0; c < 3; ++c) n2 += f.nd.at(x, y, c) * f.nd.at(x, y, c);
    return n2 > 0.01f;
}

// Screen position (top-left origin, like Image rows) of a world point.
glm::vec2 project(const Camera& c, glm::vec3 p) {
    glm::vec4 clip = c.proj * c.view * glm::vec4(p, 1.0f);
    glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {(ndc.x * 0.5f + 0.5f) * float(kSize.x), (0.5f - ndc.y * 0.5f) * float(kSize.y)};
}

float distance_to_segment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
    glm::vec2 ab = b - a;
    float t = glm::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
    return glm::length(p - (a + t * ab));
}

struct Regions {
    double bundle_core = 0, isolated = 0;  // mean AO
    int bundle_core_px = 0, isolated_px = 0;
};
constexpr float kFacing = 0.9f;  // n.z above this: the middle of a tube, not its rims

// Bundle core: geometry within 40% of the bundle's screen half-width of its axis, away from
// the line ends; isolated: geometry nearer the isolated line than the bundle.
Regions measure(const Frame& f, float min_nz = -1.0f) {
    const float inset = 0.15f * kLength;
    glm::vec2 b0 = project(f.cam, {inset, 0, 0}), b1 = project(f.cam, {kLength - inset, 0, 0});
    glm::vec2 i0 = project(f.cam, {inset, kIsolatedY, 0}), i1 = project(f.cam, {kLength - inset, kIsolatedY, 0});
    const float half_width = glm::length(project(f.cam, {kLength / 2, 0.75f, 0}) - project(f.cam, {kLength / 2, 0, 0}));
    Regions r;
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) {
            if (!geometry(f, x, y) || f.nd.at(x, y, 2) < min_nz) continue;
            glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
            float db = distance_to_segment(p, b0, b1), di = distance_to_segment(p, i0, i1);
            if (db < 0.4f * half_width) r.bundle_core += f.ao.at(x, y, 0), ++r.bundle_core_px;
            else if (di < db && di < 4.0f) r.isolated += f.ao.at(x, y, 0), ++r.isolated_px;
        }
    if (r.bundle_core_px) r.bundle_core /= r.bundle_core_px;
    if (r.isolated_px) r.isolated /= r.isolated_px;
    return r;
}

double mean_abs_diff(const Image& a, const Image& b) {
    double s = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) s += std::fabs(a.pixels[i] - b.pixels[i]);
    return s / double(a.pixels.size());
}

// RMS (0..1) of the final images' RGB over the pixels the lines cover in `a`; the background
// must be left alone in `b` (AO exactly 1 there).
double covered_rms(const Frame& a, const Frame& b) {
    double sum = 0;
    size_t n = 0, background_touched = 0;
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) {
            if (a.color.at(x, y, 3) == 0.0f) {
                background_touched += b.ao.at(x, y, 0) != 1.0f;
                continue;
            }
            for (int c = 0; c < 3; ++c) sum += std::pow(double(b.final_img.at(x, y, c) - a.final_img.at(x, y, c)), 2.0);
            n += 3;
        }
    EXPECT_EQ(background_touched, 0u) << "background pixels with AO below 1";
    EXPECT_GT(n, 1500u) << "too few covered pixels to compare";
    return n ? std::sqrt(sum / double(n)) : 0.0;
}

void expect_valid_ao(const Frame& f) {
    ASSERT_EQ(f.ao.width, kSize.x);
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) {
            float v = f.ao.at(x, y, 0);
            ASSERT_FALSE(std::isnan(v)) << "NaN at " << x << "," << y;
            ASSERT_GE(v, 0.0f);
            ASSERT_LE(v, 1.0f);
            if (!geometry(f, x, y)) {
                ASSERT_EQ(v, 1.0f) << "background AO at " << x << "," << y;
            }
        }
}

}  // namespace

TEST(lineao, Variant1MatchesGolden) {
    Frame f = render_frame();
    EXPECT_TRUE(matches_golden(f.final_img, std::string(PATHLET_TEST_SOURCE_DIR) + "/goldens/variant1_lineao.png"));
}

TEST(lineao, BundleIsDarkerThanIsolatedLine) {
    Frame f = render_frame();
    expect_valid_ao(f);
    Regions all = measure(f);
    std::printf("all pixels: bundle core AO %.3f (%d px), isolated AO %.3f (%d px)\n", all.bundle_core, all.bundle_core_px, all.isolated,
                all.isolated_px);
    Regions r = measure(f, kFacing);
    ASSERT_GT(r.bundle_core_px, 200);
    ASSERT_GT(r.isolated_px, 40);
    std::printf("bundle core AO %.3f (%d px), isolated AO %.3f (%d px)\n", r.bundle_core, r.bundle_core_px, r.isolated,
                r.isolated_px);
    EXPECT_GE(r.isolated, 0.9);
    EXPECT_LE(r.bundle_core, r.isolated - 0.15);
}

TEST(lineao, BackgroundIsTheColourPassPixelExactly) {
    Frame f = render_frame();
    size_t background = 0;
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) {
            if (f.color.at(x, y, 3) != 0.0f) continue;
            ++background;
            for (int c = 0; c < 4; ++c) ASSERT_EQ(f.lit.at(x, y, c), f.color.at(x, y, c)) << x << "," << y;
        }
    EXPECT_GT(background, size_t(kSize.x * kSize.y / 2));
}

TEST(lineao, DeterministicAcrossRuns) {
    Frame a = render_frame(), b = render_frame();
    EXPECT_EQ(a.ao.pixels, b.ao.pixels);
    EXPECT_EQ(a.final_img.pixels, b.final_img.pixels);
}

TEST(lineao, StrengthZeroIsUnoccluded) {
    Frame f = render_frame({"strength=0"});
    for (float v : f.ao.pixels) ASSERT_EQ(v, 1.0f);
}

// The quality/speed switch: the term for one pixel in four, upsampled by depth and normal.
// Meant for lines of about 3 px and more (the default width at 720p): on thinner ones a block's
// pixel is often the tube's rim, whose own convexity occludes it a little, and the upsampling
// spreads that across the line. Close to full resolution in the final image (the README gives
// the phantom's figure), never on the background, the bundle still darker, deterministic.
TEST(lineao, HalfResolutionStaysCloseToFull) {
    Frame full = render_frame({"line_width=0.45"});
    Frame half = render_frame({"line_width=0.45", "lineao.resolution=half"});
    const double rms = covered_rms(full, half);
    std::printf("half-resolution AO: final image RMS %.2f/255 against full resolution\n", 255.0 * rms);
    EXPECT_LT(rms, 8.0 / 255.0);
    EXPECT_GT(rms, 0.0) << "the switch must do something";
    const Regions r = measure(half, kFacing);
    EXPECT_LE(r.bundle_core, r.isolated - 0.08) << "the bundle must stay darker than the isolated line";
    EXPECT_EQ(render_frame({"line_width=0.45", "lineao.resolution=half"}).ao.pixels, half.ao.pixels) << "deterministic";
}

// The default s_h (16: 29 samples) is the project's speed/quality trade against the study's 32
// (58 samples): the bilateral filter averages the fixed per-pixel noise, so the final image must
// stay within a bound of RMS 2/255 over covered pixels (the phantom at 720p: 0.7-0.95).
TEST(lineao, DefaultSamplesStayWithinTwoLevelsOfTheStudys) {
    Frame study = render_frame({"samples=32"});
    Frame fewer = render_frame();
    expect_valid_ao(fewer);
    const double rms = covered_rms(study, fewer);
    std::printf("default s_h against the study's 32: final image RMS %.2f/255\n", 255.0 * rms);
    EXPECT_LE(rms, 2.0 / 255.0);
    EXPECT_GT(rms, 0.1 / 255.0) << "the default must not be the study's own count";
    const Regions r = measure(fewer, kFacing);
    EXPECT_LE(r.bundle_core, r.isolated - 0.15) << "the bundle must stay as much darker as at 58 samples";
}

TEST(lineao, RadiusAndSamplesChangeTheImage) {
    Frame base = render_frame();
    Frame r0 = render_frame({"radius=4"});
    Frame s = render_frame({"samples=58"});
    expect_valid_ao(r0);
    expect_valid_ao(s);
    EXPECT_GT(mean_abs_diff(base.ao, r0.ao), 1e-3);
    EXPECT_GT(mean_abs_diff(base.ao, s.ao), 1e-4);
}

TEST(lineao, PyramidOnAndOffAreBothValid) {
    Frame on = render_frame();
    Frame off = render_frame({"lineao.use_pyramid=false"});
    Frame box = render_frame({"gauss_pyramid.mode=box"});
    for (const Frame* f : {&on, &off, &box}) {
        expect_valid_ao(*f);
        Regions r = measure(*f, kFacing);
        EXPECT_LT(r.bundle_core, r.isolated - 0.1);
    }
    EXPECT_GT(mean_abs_diff(on.ao, off.ao), 1e-4);
    EXPECT_GT(mean_abs_diff(on.ao, box.ao), 1e-4);
}

TEST(lineao, RunningSumDiffersFromLinear) {
    Frame lin = render_frame();
    Frame rs = render_frame({"lineao.radius_growth=running_sum"});
    expect_valid_ao(rs);
    EXPECT_GT(mean_abs_diff(lin.ao, rs.ao), 1e-3);
}

TEST(lineao, OneRadiusAndExtremeDensityWeightWork) {
    Frame one = render_frame({"lineao.radii=1"});
    expect_valid_ao(one);
    Regions r = measure(one, kFacing);
    EXPECT_LT(r.bundle_core, r.isolated - 0.05);
    // delta(l) below delta0 must not reverse smoothstep's edges (guard) nor produce NaN.
    Frame tiny = render_frame({"lineao.density_weight=0.001", "lineao.delta0=0.01", "lineao.radii=8", "gauss_pyramid.levels=8"});
    expect_valid_ao(tiny);
}

TEST(lineao, GaussianPyramidDoesNotBleedIntoBackground) {
    // Level 1 of the Gaussian pyramid: background exactly where all four level-0 texels
    // below are background; geometry texels keep unit normals and depths < 1.
    Scene scene = test_scene();
    RenderOptions o;
    o.graph_path = source("graphs/variant1_lineao.json");
    o.size = kSize;
    o.sets = {"window=0"};
    o.warmup = 0;
    o.write_images = false;
    o.quiet = true;
    Image l0, l1;
    render(runtime(), scene, o, [&](const Executor& e, size_t) {
        Texture t = e.texture("pyramid"), nd = e.texture("normal_depth");
        l0 = read_texture(nd.id, nd.width, nd.height, 0, 4);  // the graph skips the level-0 copy
        l1 = read_texture(t.id, t.width / 2, t.height / 2, 1, 4);
    });
    auto n2 = [](const Image& im, int x, int y) {
        return im.at(x, y, 0) * im.at(x, y, 0) + im.at(x, y, 1) * im.at(x, y, 1) + im.at(x, y, 2) * im.at(x, y, 2);
    };
    int geometry_texels = 0;
    for (int y = 0; y < l1.height; ++y)
        for (int x = 0; x < l1.width; ++x) {
            if (n2(l1, x, y) < 0.01f) {
                ASSERT_EQ(l1.at(x, y, 3), 1.0f);
                // Image rows are top-first at both levels; level-1 row y covers level-0 rows 2y, 2y+1
                // counted from the bottom, i.e. from the top when the heights are even (120, 60).
                for (int j = 0; j < 2; ++j)
                    for (int i = 0; i < 2; ++i) ASSERT_LT(n2(l0, 2 * x + i, 2 * y + j), 0.01f) << x << "," << y;
            } else {
                ++geometry_texels;
                ASSERT_NEAR(std::sqrt(n2(l1, x, y)), 1.0f, 2e-3f);
                ASSERT_LT(l1.at(x, y, 3), 1.0f);
            }
        }
    EXPECT_GT(geometry_texels, 50);
}

TEST(lineao, DebugGraphCapturesEveryIntermediate) {
    namespace fs = std::filesystem;
    const fs::path out = fs::path(PATHLET_TEST_BINARY_DIR) / "lineao_debug_out";
    fs::remove_all(out);
    Scene scene = test_scene();
    RenderOptions o;
    o.graph_path = source("graphs/lineao_debug.json");
    o.size = kSize;
    o.sets = {"window=0", "line_width=0.15"};
    o.warmup = 0;
    o.out_dir = out.string();
    o.quiet = true;
    RenderResult res = render(runtime(), scene, o);
    for (const char* name : {"color_00000.exr", "normal_depth_00000.exr", "zoom_00000.exr",
                             "ao_00000.exr", "final_00000.png"})
        EXPECT_TRUE(fs::exists(out / "lineao_debug" / name)) << name;
    Image ao = read_image((out / "lineao_debug" / "ao_00000.exr").string());
    EXPECT_TRUE(ao.is_float);
    EXPECT_FALSE(has_nan(ao));
}

TEST(lineao, MoreStrengthDarkensInProportion) {
    // AO = 1 - strength/s_r * LineAO: the occlusion (1 - AO) of the bundle core grows with the
    // strength, in proportion while nothing clamps at 0.
    Regions half = measure(render_frame({"strength=0.5"}), kFacing);
    Regions one = measure(render_frame({"strength=1"}), kFacing);
    Regions two = measure(render_frame({"strength=2"}), kFacing);
    EXPECT_GT(half.bundle_core, one.bundle_core);
    EXPECT_GT(one.bundle_core, two.bundle_core);
    EXPECT_NEAR((1.0 - one.bundle_core) / (1.0 - half.bundle_core), 2.0, 0.15);
    EXPECT_GT(one.isolated, two.isolated - 1e-6) << "an isolated line stays (nearly) unoccluded";
}

TEST(lineao, AoMagnitudeIsPinned) {
    // The numbers of this scene at the default parameters, so a change of LineAO's strength
    // (a factor, a normalisation, a sample count) shows up here and not only as "different".
    Regions r = measure(render_frame(), kFacing);
    EXPECT_NEAR(r.bundle_core, 0.822, 0.02);
    EXPECT_NEAR(r.isolated, 1.0, 0.005);
}

// A whole exponent is compiled in as products (shaders/pow_whole.glsl, pathlet::whole_exponent):
// it must draw what pow() draws (an exponent a hair off a whole number takes the pow path), and
// the exponent must matter in this scene, or the comparison would prove nothing.
TEST(lineao, WholeExponentDrawsWhatPowDraws) {
    for (const char* e : {"100", "7"}) {
        Frame whole = render_frame({std::string("lineao.exponent=") + e});
        Frame powed = render_frame({std::string("lineao.exponent=") + e + ".0001"});
        EXPECT_LT(max_abs_difference(whole.ao, powed.ao), 2e-3f) << "exponent " << e;
    }
    EXPECT_GT(mean_abs_diff(render_frame({"lineao.exponent=1"}).ao, render_frame({"lineao.exponent=100"}).ao), 1e-3)
        << "the exponent must change the AO here";
}

// bilateral compiles its normal weight's power in (a whole power as products, 0 as no normal
// weight): each variant must draw what pow() draws with a power a hair away, and the power must
// matter in this scene, or the comparison would prove nothing.
TEST(lineao, BilateralCompiledNormalPowerDrawsWhatPowDraws) {
    for (const char* e : {"1", "3"}) {
        Frame whole = render_frame({std::string("bilateral.normal_power=") + e});
        Frame powed = render_frame({std::string("bilateral.normal_power=") + e + ".0001"});
        std::printf("bilateral normal_power %s against %s.0001: max |difference| %.2e\n", e, e,
                    max_abs_difference(whole.final_img, powed.final_img));
        EXPECT_LT(max_abs_difference(whole.final_img, powed.final_img), 1.5f / 255.0f) << "normal_power " << e;
    }
    // pow(c, 0.0001) is ~1 except where normals face away (c = 0): the mean stays tiny.
    const Frame none = render_frame({"bilateral.normal_power=0"});
    const double near_zero = mean_abs_diff(none.final_img, render_frame({"bilateral.normal_power=0.0001"}).final_img);
    std::printf("bilateral normal_power 0 against 0.0001: mean |difference| %.2e\n", near_zero);
    EXPECT_LT(near_zero, 2e-4) << "normal_power 0 (no normal weight) against pow(c, 0.0001)";
    const double matters = mean_abs_diff(none.final_img, render_frame({"bilateral.normal_power=8"}).final_img);
    std::printf("bilateral normal_power 0 against 8: mean |difference| %.2e\n", matters);
    EXPECT_GT(matters, 1e-4) << "the normal weight must change the image here";
}
