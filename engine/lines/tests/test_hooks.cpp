// A fade strategy as one GLSL file in every line pipeline: a colour hook with its
// parameters declared in the shader (@param), named by the graph next to it, drawn by the
// opaque G-buffer (gbuffer), the OIT lists (fill_list, real transparency) and ISL; its
// parameters validated, settable and bound; bad hooks named by file and line. Two straight
// pathlets seen square-on (tests/support): age 1 at the left (tail) end, 0 at the right (head).
#include "frame_capture.hpp"
#include "graph/graph_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

namespace fs = std::filesystem;
using namespace pathlet;

namespace {

const glm::ivec2 kSize{400, 100};

Runtime& rt() { return test_runtime(); }

std::string dir() {
    static const std::string d = test_scratch_dir("pathlet_hooks");
    return d;
}
std::string write(const std::string& name, const std::string& text) {
    const std::string p = dir() + "/" + name;
    std::ofstream(p) << text;
    return p;
}

// Tints towards u_tint with age and ramps opacity down with age; both by parameter.
const char* kAgeHook = R"(#version 450 core
// A test strategy: the tail turns to a colour and fades out.
#include "line_hooks.glsl"
uniform vec3 u_tint;          // @param color #0000ff "colour the tail turns to"
uniform float u_amount;       // @param 1 [0, 1] "how far the tail turns"
uniform float u_opacity_ramp; // @param 0 [0, 1] "how much of the opacity the tail loses"
vec4 line_color_hook(vec4 rgba, LinePoint p) {
    return vec4(mix(rgba.rgb, u_tint, u_amount * p.age), rgba.a * (1.0 - u_opacity_ramp * p.age));
}
)";

// One graph per pipeline, each with the hook next to it.
void write_graphs() {
    write("age_tint.frag", kAgeHook);
    write("gbuffer_hooked.json", R"({"version": 1, "resources": {"color": {"format": "rgba8"}},
      "passes": [{"name": "lines", "type": "gbuffer", "params": {"window": 10, "line_width": 1.5, "halo": 0,
                  "color_hook": "age_tint.frag"}, "outputs": {"color": "color"}}],
      "outputs": [{"resource": "color"}]})");
    write("oit_hooked.json", R"({"version": 1,
      "passes": [
        {"name": "clear", "type": "clear_list", "outputs": {"heads": "heads", "counter": "counter"}},
        {"name": "fill", "type": "fill_list", "params": {"window": 10, "line_width": 1.5, "halo": 0,
         "color_hook": "age_tint.frag", "amount": 0, "opacity_ramp": 1},
         "inputs": {"heads": "heads", "counter": "counter"}, "outputs": {"nodes": "nodes"}},
        {"name": "resolve", "type": "resolve_list", "inputs": {"heads": "heads", "nodes": "nodes"},
         "outputs": {"color": "color", "front_alpha": "alpha"}}],
      "resources": {"heads": {}, "counter": {"kind": "buffer"}, "nodes": {"kind": "buffer"}, "color": {}, "alpha": {}},
      "outputs": [{"resource": "color"}, {"resource": "alpha"}]})");
    write("isl_hooked.json", R"({"version": 1, "resources": {"color": {"format": "rgba8"}},
      "passes": [{"name": "isl", "type": "isl", "params": {"window": 10, "line_width": 1.5, "halo": 0,
                  "color_hook": "age_tint.frag"}, "outputs": {"color": "color"}}],
      "outputs": [{"resource": "color"}]})");
}

Frame render(const std::string& graph, std::vector<std::string> sets, const std::vector<std::string>& names) {
    write_graphs();
    RenderOptions opt;
    opt.graph_path = dir() + "/" + graph;
    opt.sets = std::move(sets);
    opt.size = kSize;
    opt.camera_path = write_square_on_camera(dir() + "/camera.json");
    opt.time.start = 10.0;
    return render_frame(rt(), two_speed_lines_scene(), opt, names);
}

// Mean of channel c over the covered pixels (alpha > 0.5 in `cover`) of columns [x0, x1).
double mean_over(const Image& img, const Image& cover, int c, int x0, int x1, int cover_channel = 3) {
    double sum = 0;
    int n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = x0; x < x1; ++x)
            if (cover.at(x, y, cover_channel) > 0.5f) sum += img.at(x, y, c), ++n;
    return n ? sum / n : -1.0;
}

// The fast line spans x = -15..25, columns 106..294 (4.7 px a unit, x = 5 at column 200): columns
// 106..140 are its tail (age 1..0.82), 250..290 its head (age 0.24..0.02). The slow line lies
// between them (columns 176..223).
constexpr int kTail0 = 106, kTail1 = 140, kHead0 = 250, kHead1 = 290;

std::string error_of(const std::string& graph, std::vector<std::string> sets = {}) {
    try {
        render(graph, std::move(sets), {"color"});
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Hooks, ColourHookWithParametersInTheOpaqueGBuffer) {
    const Frame f = render("gbuffer_hooked.json", {}, {"color"});
    const Image& c = f["color"];
    // The tail turned blue (the tint); the head keeps the speed map's colour (red for the fast
    // line: no blue in the green_red map).
    const double tail_b = mean_over(c, c, 2, kTail0, kTail1), head_b = mean_over(c, c, 2, kHead0, kHead1);
    EXPECT_GT(tail_b, 0.75) << "the tail should have turned to the tint";
    EXPECT_LT(head_b, 0.3);
    // The parameters reach the hook: amount 0 is the plain kit colour, ...
    const Frame plain = render("gbuffer_hooked.json", {"lines.amount=0"}, {"color"});
    EXPECT_LT(mean_over(plain["color"], plain["color"], 2, kTail0, kTail1), 0.2);
    // ... and tint = #00ff00 turns the tail green instead.
    const Frame green = render("gbuffer_hooked.json", {"lines.tint=#00ff00"}, {"color"});
    EXPECT_GT(mean_over(green["color"], green["color"], 1, kTail0, kTail1), 0.75);
    EXPECT_LT(mean_over(green["color"], green["color"], 2, kTail0, kTail1), 0.2);
}

TEST(Hooks, TheSameHookRampsRealOpacityInTheOitPipeline) {
    const Frame f = render("oit_hooked.json", {}, {"color", "alpha"});
    const Image& a = f["alpha"];
    // front_alpha: the nearest fragment's opacity, 1 - age: low at the tail, near 1 at the head.
    double tail = 0, head = 0;
    int nt = 0, nh = 0;
    for (int y = 0; y < a.height; ++y) {
        for (int x = kTail0; x < kTail1; ++x)
            if (a.at(x, y, 0) > 0.0f) tail += a.at(x, y, 0), ++nt;
        for (int x = kHead0; x < kHead1; ++x)
            if (a.at(x, y, 0) > 0.0f) head += a.at(x, y, 0), ++nh;
    }
    ASSERT_GT(nt, 0);
    ASSERT_GT(nh, 0);
    tail /= nt;
    head /= nh;
    EXPECT_LT(tail, 0.5) << "the tail is mostly transparent";
    EXPECT_GT(head, 0.8) << "the head is nearly opaque";
    // Not a screen door: the opacity varies smoothly, so many distinct levels appear.
    std::set<int> levels;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            if (a.at(x, y, 0) > 0.0f) levels.insert(int(a.at(x, y, 0) * 255.0f));
    EXPECT_GT(levels.size(), 20u);
    // Without the ramp, every covered pixel is as opaque as the edge coverage allows.
    const Frame opaque = render("oit_hooked.json", {"fill.opacity_ramp=0"}, {"alpha"});
    EXPECT_GT(mean_over(opaque["alpha"], opaque["alpha"], 0, kTail0, kTail1, 0), 0.8);
}

TEST(Hooks, TheSameHookColoursIllustratedStreamlines) {
    const Frame f = render("isl_hooked.json", {}, {"color"});
    const Frame plain = render("isl_hooked.json", {"isl.amount=0"}, {"color"});
    const Image &c = f["color"], &p = plain["color"];
    // ISL's image is opaque everywhere; the lines are where the two differ from the background.
    double diff_tail = 0, diff_head = 0;
    for (int y = 0; y < c.height; ++y) {
        for (int x = kTail0; x < kTail1; ++x) diff_tail += std::fabs(c.at(x, y, 2) - p.at(x, y, 2));
        for (int x = kHead0; x < kHead1; ++x) diff_head += std::fabs(c.at(x, y, 2) - p.at(x, y, 2));
    }
    EXPECT_GT(diff_tail, 5.0) << "the hook's tint shows at the tail";
    EXPECT_GT(diff_tail, 3.0 * diff_head) << "and fades towards the head (age 0)";
}

TEST(Hooks, AMisspeltHookParameterIsAGraphErrorWithDidYouMean) {
    write_graphs();
    std::string msg = error_of("gbuffer_hooked.json", {"lines.amout=0.5"});
    EXPECT_NE(msg.find("unknown parameter 'amout'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("did you mean 'amount'"), std::string::npos) << msg;
    // In the file too, with its pointer.
    write("typo.json", R"({"version": 1, "resources": {"color": {"format": "rgba8"}},
      "passes": [{"name": "lines", "type": "gbuffer", "params": {"color_hook": "age_tint.frag", "opacity_rmap": 1},
                  "outputs": {"color": "color"}}], "outputs": [{"resource": "color"}]})");
    msg = error_of("typo.json");
    EXPECT_NE(msg.find("/passes/0/params/opacity_rmap"), std::string::npos) << msg;
    EXPECT_NE(msg.find("did you mean 'opacity_ramp'"), std::string::npos) << msg;
}

TEST(Hooks, ABadParamLineAndAMissingFunctionNameFileAndLine) {
    write_graphs();
    write("bad_param.frag", "#version 450 core\n#include \"line_hooks.glsl\"\n"
                            "uniform float u_gain; // @param loud [0, 1] \"gain\"\n"
                            "vec4 line_color_hook(vec4 rgba, LinePoint p) { return rgba * u_gain; }\n");
    std::string msg = error_of("gbuffer_hooked.json", {"lines.color_hook=bad_param.frag"});
    EXPECT_NE(msg.find("bad_param.frag:3: @param"), std::string::npos) << msg;
    write("misnamed.frag", "#version 450 core\n#include \"line_hooks.glsl\"\n\n"
                           "vec4 line_colour_hook(vec4 rgba, LinePoint p) { return rgba; }\n");
    msg = error_of("gbuffer_hooked.json", {"lines.color_hook=misnamed.frag"});
    EXPECT_NE(msg.find("misnamed.frag:4: a colour hook defines vec4 line_color_hook(vec4 rgba, LinePoint p)"),
              std::string::npos)
        << msg;
    EXPECT_NE(msg.find("'line_colour_hook' instead"), std::string::npos) << msg;
    // A width hook must define the width function.
    msg = error_of("gbuffer_hooked.json", {"lines.width_hook=age_tint.frag"});
    EXPECT_NE(msg.find("a width hook defines float line_width_hook(LinePoint p)"), std::string::npos) << msg;
}

TEST(Hooks, HookNamesStayOnTheShaderPath) {
    write_graphs();
    for (const char* bad : {"../age_tint.frag", "/etc/passwd.frag", "sub/x.frag", ".hidden.frag"}) {
        const std::string msg = error_of("gbuffer_hooked.json", {std::string("lines.color_hook=") + bad});
        EXPECT_NE(msg.find("without folders or '..'"), std::string::npos) << bad << ": " << msg;
    }
    EXPECT_NE(error_of("gbuffer_hooked.json", {"lines.color_hook=age_tint.txt"}).find("ends in .frag, .geom or .glsl"),
              std::string::npos);
    const std::string missing = error_of("gbuffer_hooked.json", {"lines.color_hook=nowhere.frag"});
    EXPECT_NE(missing.find("hook file 'nowhere.frag' not found; searched:"), std::string::npos) << missing;
    EXPECT_NE(missing.find(dir()), std::string::npos) << "the graph's folder is searched: " << missing;
    // An include may not climb out of the shader path either.
    write("climb.frag", "#version 450 core\n#include \"../../etc/hosts\"\n");
    EXPECT_NE(error_of("gbuffer_hooked.json", {"lines.color_hook=climb.frag"}).find("climb.frag:2: #include"),
              std::string::npos);
}

TEST(Hooks, ParametersOfAnAngleBracketIncludeArePassParameters) {
    // The compiler inlines #include <x> as it does "x": the @param lines there count as well.
    write_graphs();
    write("gain_params.glsl", "uniform float u_gain; // @param 1 [0, 4] \"gain of the colour\"\n");
    write("gain.frag", "#version 450 core\n#include \"line_hooks.glsl\"\n#include <gain_params.glsl>\n"
                       "vec4 line_color_hook(vec4 rgba, LinePoint p) { return vec4(rgba.rgb * u_gain, rgba.a); }\n");
    EXPECT_EQ(error_of("gbuffer_hooked.json", {"lines.color_hook=gain.frag", "lines.gain=0.5"}), "");
    const std::string msg = error_of("gbuffer_hooked.json", {"lines.color_hook=gain.frag", "lines.gian=0.5"});
    EXPECT_NE(msg.find("did you mean 'gain'"), std::string::npos) << msg;
}

TEST(Hooks, AGlslHookIsCompiledAsTheStageItsRoleNeeds) {
    write_graphs();
    write("age_tint.glsl", kAgeHook);  // not .frag: compiled as the colour hook's fragment stage
    const Frame f = render("gbuffer_hooked.json", {"lines.color_hook=age_tint.glsl"}, {"color"});
    const Frame g = render("gbuffer_hooked.json", {}, {"color"});
    EXPECT_EQ(f["color"].pixels, g["color"].pixels);
}

// The lesson of plugins/example_fade: one GLSL file as variant 1's width hook and variant 2's
// colour hook, in graphs that extend the shipped ones. Both run, and change the picture.
TEST(Hooks, TheExampleStrategyExtendsVariant1AndVariant2) {
    const std::string ex = std::string(PATHLET_SOURCE_DIR) + "/plugins/example_fade/";
    auto frame = [&](const std::string& graph) {
        RenderOptions opt;
        opt.graph_path = graph;
        opt.size = {160, 120};
        opt.time.start = 9.0;
        opt.sets = {"overlay=false"};
        return render_frame(rt(), helix_bundle_scene(), opt, {"final"})["final"];
    };
    const std::string shipped = std::string(PATHLET_SOURCE_DIR) + "/graphs/";
    const Image v1 = frame(shipped + "variant1_lineao.json"), v1_fade = frame(ex + "speed_fade_v1.json");
    const Image v2 = frame(shipped + "variant2_oit.json"), v2_fade = frame(ex + "speed_fade_oit.json");
    auto ink = [](const Image& img) {  // how much of the image the lines darken
        double s = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) s += 1.0 - img.at(x, y, 1);
        return s;
    };
    EXPECT_NE(v1.pixels, v1_fade.pixels);
    EXPECT_NE(v2.pixels, v2_fade.pixels);
    EXPECT_LT(ink(v1_fade), ink(v1)) << "tapered pathlets cover less";
    EXPECT_GT(ink(v1_fade), 0.2 * ink(v1)) << "but they are there";
    EXPECT_LT(ink(v2_fade), ink(v2) * 1.5);
    EXPECT_GT(ink(v2_fade), 0.1 * ink(v2));
}
