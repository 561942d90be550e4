// A newcomer's fade, as the README teaches it: the "Writing a fade strategy" GLSL
// block, read from README.md itself and saved as my_fade.glsl, works as printed (no #version,
// no boilerplate) in variant 1, variant 2 and isl, through a graph that extends them and
// through --set from the hook's own folder, and both give the same picture. Swapping variant
// 2's hook needs no nulls (the replaced hook's parameters go, with a note); a misspelt
// parameter still gets a did-you-mean; an error in a hook names its file and line; a hook path
// is the user's on the command line, never a graph's or an experiment's.
#include "cli_run.hpp"
#include "frame_capture.hpp"
#include "graph/graph_model.hpp"
#include "image_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace pathlet;

namespace {

const std::string kSrc = PATHLET_SOURCE_DIR;

std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// The fenced GLSL block under the README's "Writing a fade strategy" heading, as printed.
std::string readme_fade() {
    const std::string text = slurp(kSrc + "/README.md");
    const size_t heading = text.find("Writing a fade strategy");
    const size_t a = heading == std::string::npos ? heading : text.find("```glsl\n", heading);
    const size_t b = a == std::string::npos ? a : text.find("\n```", a + 8);
    return b == std::string::npos ? "" : text.substr(a + 8, b - a - 8) + "\n";
}

// A user's folder: the README's fade as my_fade.glsl and a graph per pipeline extending a
// shipped one with it (fade_v2.json is the README's variant 2 example, four lines).
const std::string& fade_dir() {
    static const std::string dir = [] {
        const std::string d = test_scratch_dir("pathlet_fade_guide") + "/my_fades";
        fs::create_directories(d);
        write(d + "/my_fade.glsl", readme_fade());
        write(d + "/fade_v1.json",
              R"({"extends": "variant1_lineao", "passes": [{"name": "gbuffer", "params": {"width_hook": "my_fade.glsl"}}]})");
        write(d + "/fade_v2.json", R"({"extends": "variant2_oit",
 "passes": [{"name": "fill_list",
             "params": {"color_hook": "my_fade.glsl"}}]}
)");
        write(d + "/fade_isl.json",
              R"({"extends": "isl", "passes": [{"name": "isl", "params": {"color_hook": "my_fade.glsl"}}]})");
        return d;
    }();
    return dir;
}

struct Rendered {
    CliRun run;
    Image image;
};

// `pathlet render ARGS` run from `cwd` (default: the fade's folder), one small frame.
Rendered render(const std::string& args, const std::string& tag, const std::string& cwd = fade_dir()) {
    const std::string out = fade_dir() + "/out_" + tag;
    Rendered r;
    r.run = pathlet_cli("render " + args + " --phantom small --time 2 --size 160x90 --set overlay=false --out " + out,
                        "cd '" + cwd + "' &&");
    if (!fs::exists(out)) return r;  // a render refused before anything was written
    for (const auto& e : fs::recursive_directory_iterator(out, fs::directory_options::none))
        if (e.path().extension() == ".png") r.image = read_image(e.path().string());
    return r;
}

// How much the lines darken the picture (the background is white).
double ink(const Image& img) {
    double s = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) s += 1.0 - img.at(x, y, 1);
    return s;
}

struct Pipeline {
    std::string graph, ext, pass, hook;
};
const Pipeline kPipelines[] = {{"variant1_lineao", "fade_v1.json", "gbuffer", "width_hook"},
                               {"variant2_oit", "fade_v2.json", "fill_list", "color_hook"},
                               {"isl", "fade_isl.json", "isl", "color_hook"}};

}  // namespace

TEST(FadeGuide, TheReadmeSnippetIsOnlyAFunction) {
    const std::string hook = readme_fade();
    ASSERT_NE(hook.find("line_width_hook"), std::string::npos) << "no fade snippet under the README's heading";
    EXPECT_EQ(hook.find("#version"), std::string::npos) << "the README prints it without a version line";
}

TEST(FadeGuide, WorksInEveryPipelineThroughExtendsAndThroughSetFromItsFolder) {
    for (const Pipeline& p : kPipelines) {
        SCOPED_TRACE(p.graph);
        const Rendered ext = render(p.ext, p.graph + "_ext");
        ASSERT_EQ(ext.run.code, 0) << ext.run.err;
        const Rendered set = render(p.graph + " --set " + p.pass + "." + p.hook + "=my_fade.glsl", p.graph + "_set");
        ASSERT_EQ(set.run.code, 0) << set.run.err;
        const Rendered plain = render(p.graph, p.graph + "_plain");
        ASSERT_EQ(plain.run.code, 0) << plain.run.err;
        ASSERT_EQ(ext.image.width, 160);
        EXPECT_EQ(ext.image.pixels, set.image.pixels) << "extends and --set name the same file";
        EXPECT_NE(ext.image.pixels, plain.image.pixels) << "the fade changes the picture";
        EXPECT_LT(ink(ext.image), ink(plain.image)) << "faded pathlets darken less";
        EXPECT_GT(ink(ext.image), 0.1 * ink(plain.image)) << "but they are there";
    }
}

TEST(FadeGuide, SwappingVariant2sHookDropsTheEndFadesParametersWithANote) {
    // The README's four-line graph: no nulls for tail_fade and head_fade.
    const Rendered ext = render("fade_v2.json", "v2_note");
    ASSERT_EQ(ext.run.code, 0) << ext.run.err;
    const std::string& err = ext.run.err;
    EXPECT_NE(err.find("note: fade_v2.json: pass 'fill_list': color_hook 'my_fade.glsl' replaces "
                       "'fade_opacity.frag', so the parameters set for the replaced hook are dropped: head_fade, tail_fade"),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("the graph variables that fed only them: head_fade, tail_fade"), std::string::npos) << err;
    // The same swap on the command line says the same of its --set.
    const Rendered set = render("variant2_oit --set fill_list.color_hook=my_fade.glsl", "v2_set_note");
    ASSERT_EQ(set.run.code, 0) << set.run.err;
    EXPECT_NE(set.run.err.find("note: --set fill_list.color_hook=" + fade_dir() +
                               "/my_fade.glsl: pass 'fill_list': color_hook 'my_fade.glsl' replaces 'fade_opacity.frag'"),
              std::string::npos)
        << set.run.err;
    EXPECT_EQ(ext.image.pixels, set.image.pixels);
    // A hook that keeps the end fade keeps its parameters: no note.
    const Rendered same = render("variant2_oit --set fill_list.color_hook=fade_opacity.frag", "v2_same");
    ASSERT_EQ(same.run.code, 0) << same.run.err;
    EXPECT_EQ(same.run.err.find("dropped"), std::string::npos) << same.run.err;
}

TEST(FadeGuide, AParameterTheNewHookLacksIsStillAnErrorWithDidYouMean) {
    Runtime& rt = test_runtime();
    // Set by the graph that swaps the hook: not dropped, named with a did-you-mean.
    write(fade_dir() + "/fade_typo.json", R"({"extends": "variant2_oit", "passes": [{"name": "fill_list",
      "params": {"color_hook": "my_fade.glsl", "keep_slwo": 0.2, "tail_fade": 0.3}}]})");
    GraphFile g = parse_graph_file(fade_dir() + "/fade_typo.json");
    std::vector<Diagnostic> d;
    apply_overrides(g, {}, rt.registry, d);
    const auto more = validate_graph(g, rt.registry);
    d.insert(d.end(), more.begin(), more.end());
    std::string all;
    for (const auto& x : d) all += x.str() + "\n";
    EXPECT_NE(all.find("/passes/1/params/keep_slwo: unknown parameter 'keep_slwo'"), std::string::npos) << all;
    EXPECT_NE(all.find("did you mean 'keep_slow'"), std::string::npos) << all;
    EXPECT_NE(all.find("/passes/1/params/tail_fade: unknown parameter 'tail_fade'"), std::string::npos) << all;
    // After a --set swap, a later --set of the new hook's parameter is checked against it.
    GraphFile v2 = parse_graph_file(kSrc + "/graphs/variant2_oit.json");
    std::vector<Diagnostic> sd;
    const auto sets = rt.user_sets({"fill_list.color_hook=" + fade_dir() + "/my_fade.glsl", "fill_list.keep_slwo=0.2",
                                    "fill_list.keep_fast=0.9"});
    apply_overrides(v2, sets, rt.registry, sd, rt.user_files);
    ASSERT_EQ(sd.size(), 1u);
    EXPECT_NE(sd[0].message.find("did you mean 'keep_slow'"), std::string::npos) << sd[0].str();
    ASSERT_EQ(v2.notes.size(), 1u);
    EXPECT_TRUE(validate_graph(v2, rt.registry).empty());
    // The variables that fed only the dropped parameters are gone: --set tail_fade is no silent no-op.
    EXPECT_FALSE(std::any_of(v2.variables.begin(), v2.variables.end(), [](const auto& v) { return v.name == "tail_fade"; }));
}

TEST(FadeGuide, AnErrorInAHookNamesItsFileAndLine) {
    Runtime& rt = test_runtime();
    const std::string d = fade_dir();
    write(d + "/broken.glsl", "// a fade with a typo on line 3\nfloat line_width_hook(LinePoint p) {\n"
                              "    return 1.0 - p.agee;\n}\n");
    write(d + "/versioned.glsl", "#version 450 core\n#include \"line_hooks.glsl\"\n\n"
                                 "float line_width_hook(LinePoint p) { return undeclared; }\n");
    write(d + "/fade_helper.glsl", "// included by uses_helper.glsl\nfloat helper(LinePoint p) { return p.age * ; }\n");
    write(d + "/uses_helper.glsl", "#include \"fade_helper.glsl\"\nfloat line_width_hook(LinePoint p) { return helper(p); }\n");
    auto error_of = [&](const std::string& hook) {
        RenderOptions opt;
        opt.graph_path = d + "/fade_v1.json";
        opt.sets = rt.user_sets({"gbuffer.width_hook=" + d + "/" + hook});
        opt.size = {32, 18};
        opt.time.start = 5;
        try {
            render_frame(rt, helix_bundle_scene(), opt, {"final"});
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    std::string msg = error_of("broken.glsl");
    EXPECT_NE(msg.find("GLSL compile error in " + d + "/broken.glsl"), std::string::npos) << msg;
    EXPECT_NE(msg.find(d + "/broken.glsl:3:"), std::string::npos) << msg;
    msg = error_of("versioned.glsl");  // its own version line: the same numbering
    EXPECT_NE(msg.find(d + "/versioned.glsl:4:"), std::string::npos) << msg;
    msg = error_of("uses_helper.glsl");  // through an include: the included file's line
    EXPECT_NE(msg.find(d + "/fade_helper.glsl:2:"), std::string::npos) << msg;
}

TEST(FadeGuide, AHookPathIsTheUsersOnTheCommandLineOnly) {
    const std::string d = fade_dir(), parent = fs::path(d).parent_path().string();
    // Relative with a folder, from elsewhere: the same file, the same picture.
    const Rendered rel = render("variant1_lineao --set gbuffer.width_hook=my_fades/my_fade.glsl", "rel", parent);
    ASSERT_EQ(rel.run.code, 0) << rel.run.err;
    const Rendered ext = render("fade_v1.json", "rel_ext");
    EXPECT_EQ(rel.image.pixels, ext.image.pixels);
    // Absolute, and a path to no file (named with where it looked).
    CliRun abs = pathlet_cli("graph variant1_lineao --set gbuffer.width_hook=" + d + "/my_fade.glsl");
    EXPECT_EQ(abs.code, 0) << abs.err;
    CliRun none = pathlet_cli("graph variant1_lineao --set gbuffer.width_hook=nowhere/x.glsl", "cd '" + d + "' &&");
    EXPECT_EQ(none.code, 1);
    EXPECT_NE(none.err.find("no hook file 'nowhere/x.glsl' (looked for " + d + "/nowhere/x.glsl)"), std::string::npos)
        << none.err;
    // A graph file names hooks by file name only, whatever it points at.
    write(d + "/abs_hook.json", R"({"extends": "variant1_lineao", "passes": [{"name": "gbuffer", "params": {"width_hook": ")" +
                                    d + R"(/my_fade.glsl"}}]})");
    CliRun graph = pathlet_cli("validate " + d + "/abs_hook.json");
    EXPECT_EQ(graph.code, 1);
    EXPECT_NE(graph.err.find("/passes/0/params/width_hook: width_hook '" + d + "/my_fade.glsl': a hook a graph names"),
              std::string::npos)
        << graph.err;
    // So does an experiment file's "set": it is a stranger's file too.
    write(d + "/abs_hook_exp.json", R"({"graphs": ["variant1_lineao"], "data": [{"phantom": "small"}], "sizes": ["32x18"],
      "frames": 1, "warmup": 0, "set": ["gbuffer.width_hook=)" + d + R"(/my_fade.glsl"]})");
    CliRun exp = pathlet_cli("bench --experiment " + d + "/abs_hook_exp.json --out " + d + "/exp_out --quiet");
    EXPECT_NE(exp.code, 0);
    EXPECT_NE(exp.err.find("a hook a graph names is a file name"), std::string::npos) << exp.err;
    EXPECT_FALSE(fs::exists(d + "/exp_out/results.json")) << "nothing run, nothing written";
}

TEST(FadeGuide, AHookAsTheGraphVariablesDefaultBringsItsOwnParameters) {
    const std::string d = fade_dir();
    write(d + "/pulse_fade.glsl",
          "uniform float u_pulse_rate;  // @param 2 [0.1, 10] \"pulses per second\"\n"
          "vec4 line_color_hook(vec4 rgba, LinePoint p) {\n"
          "    return vec4(rgba.rgb, rgba.a * (0.55 + 0.45 * sin(6.2831853 * u_pulse_rate * p.time)));\n}\n");
    // The hook as the default of variant 2's variable, its own parameter set on the pass.
    write(d + "/pulse_v2.json", R"({"extends": "variant2_oit", "variables": {"color_hook": {"default": "pulse_fade.glsl"}},
 "passes": [{"name": "fill_list", "params": {"pulse_rate": 3}}]})");
    const Rendered ext = render("pulse_v2.json", "pulse_ext");
    ASSERT_EQ(ext.run.code, 0) << ext.run.err;
    EXPECT_NE(ext.run.err.find("pulse_v2.json: pass 'fill_list': color_hook 'pulse_fade.glsl' replaces "
                               "'fade_opacity.frag', so the parameters set for the replaced hook are dropped: head_fade, "
                               "tail_fade"),
              std::string::npos)
        << ext.run.err;
    // The same on the command line, and as one value: the file with its parameters.
    const Rendered set = render("variant2_oit --set color_hook=pulse_fade.glsl --set fill_list.pulse_rate=3", "pulse_set");
    ASSERT_EQ(set.run.code, 0) << set.run.err;
    EXPECT_EQ(ext.image.pixels, set.image.pixels);
    write(d + "/pulse_obj.json", R"({"extends": "variant2_oit", "passes": [{"name": "fill_list",
 "params": {"color_hook": {"file": "pulse_fade.glsl", "pulse_rate": 3}}}]})");
    const Rendered obj = render("pulse_obj.json", "pulse_obj");
    ASSERT_EQ(obj.run.code, 0) << obj.run.err;
    EXPECT_EQ(obj.image.pixels, ext.image.pixels);
    // The hook's own parameter reaches it.
    const Rendered slow = render("pulse_v2.json --set fill_list.pulse_rate=0.5", "pulse_slow");
    ASSERT_EQ(slow.run.code, 0) << slow.run.err;
    EXPECT_NE(slow.image.pixels, ext.image.pixels);
    // A set after the swap is read against the new hook: the end fade's parameter is no more.
    const Rendered stale = render("pulse_v2.json --set fill_list.tail_fade=0.3", "pulse_stale");
    EXPECT_EQ(stale.run.code, 1) << stale.run.err;
    EXPECT_NE(stale.run.err.find("unknown parameter 'tail_fade'"), std::string::npos) << stale.run.err;
}
