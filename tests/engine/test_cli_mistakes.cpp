// A researcher's day without surprises, through the command line as a user types it:
// a graph without "name" is named after its file; every mistake is told at once, with the fix
// (did-you-mean for graph names, commands and pass types; a time outside the data), exit 2 and
// nothing created; `validate` counts every error and compiles every hook; a hook's errors name
// its own file and line; a hook next to the graph wins over a shipped one; a hook's parameters
// are listed with their docs.
#include "cli_run.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <regex>
#include <sstream>

namespace {

// An empty folder of the user's, for one test.
std::string user_dir(const std::string& name) {
    const fs::path d = fs::path(PATHLET_TEST_BINARY_DIR) / "cli_mistakes" / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d.string();
}
void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }
// `pathlet ARGS` run in `dir`.
CliRun in(const std::string& dir, const std::string& args) { return pathlet_cli(args, "cd '" + dir + "' &&"); }
std::vector<std::string> entries(const std::string& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}
std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

const char* kSmall = " --phantom small --size 64x36 --set overlay=false";

// The README's colour hook with a wrong field on line 4.
const char* kWrongField = R"(uniform float u_keep;  // @param 0.5 [0, 1] "how much of the opacity to keep"
vec4 line_color_hook(vec4 rgba, LinePoint p) {
    float kept = u_keep;
    return vec4(rgba.rgb, rgba.a * kept * p.agee);
}
)";

}  // namespace

TEST(CliMistakes, AnUnknownGraphIsOneErrorLineWithTheFixAndNothingIsMade) {
    const std::string d = user_dir("unknown_graph");
    struct Case {
        std::string args, given, hint;
    } cases[] = {{"render variant1_lineoa" + std::string(kSmall), "variant1_lineoa", "variant1_lineao"},
                 {"graph variant1_lineoa --plan --phantom small", "variant1_lineoa", "variant1_lineao"},
                 {"validate variant1_lineoa", "variant1_lineoa", "variant1_lineao"},
                 {"quality variant1_lineoa --phantom small", "variant1_lineoa", "variant1_lineao"},
                 {"bench variant1_lineao,ils --frames 1 --phantom small", "ils", "isl"},
                 {"render fade_v1.jsn" + std::string(kSmall), "fade_v1.jsn", "fade_v1.json"}};
    write(d + "/fade_v1.json", R"({"extends": "variant1_lineao"})");
    for (const auto& c : cases) {
        SCOPED_TRACE(c.args);
        const CliRun r = in(d, c.args);
        EXPECT_EQ(r.code, 2) << r.err;
        EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line:\n" << r.err;
        EXPECT_EQ(r.err.rfind("error: no graph '" + c.given + "'", 0), 0u) << r.err;
        EXPECT_NE(first_line(r.err).find("(did you mean '" + c.hint + "'?)"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("data:"), std::string::npos) << "nothing loaded before the name is known good";
        EXPECT_EQ(entries(d), std::vector<std::string>{"fade_v1.json"}) << "nothing created";
    }
}

TEST(CliMistakes, AnUnknownCommandOrPassTypeGetsTheClosestName) {
    CliRun r = pathlet_cli("rendr");
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.err.rfind("error: unknown command 'rendr' (did you mean 'render'?)", 0), 0u) << r.err;
    r = pathlet_cli("passes --describe lineoa");
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.err.rfind("error: no pass type 'lineoa' (did you mean 'lineao'?)", 0), 0u) << r.err;
}

TEST(CliMistakes, AUsageErrorNamesItsCommandOnce) {
    for (const std::string cmd : {"render", "bench isl", "graph isl", "quality"}) {
        SCOPED_TRACE(cmd);
        const std::string name = cmd.substr(0, cmd.find(' '));
        const CliRun r = pathlet_cli(cmd + " --size 160by90");
        EXPECT_EQ(r.code, 2);
        EXPECT_EQ(r.err.rfind("pathlet " + name + ": --size '160by90'", 0), 0u) << r.err;
        EXPECT_EQ(r.err.find(name + ": " + name + ":"), std::string::npos) << r.err;
    }
}

TEST(CliMistakes, DataMessagesNameTheUsersOptionsNotTheCppOnes) {
    const std::string d = user_dir("data_messages");
    write(d + "/rows.txt", "0 0 0 1 0 0 2 0 0\n0 1 0 1 1 0 2 1 0\n");
    CliRun r = pathlet_cli("info " + d + "/rows.txt");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE((r.out + r.err).find("--time-step SECONDS"), std::string::npos) << r.out << r.err;
    EXPECT_EQ((r.out + r.err).find("LoadOptions"), std::string::npos) << r.out << r.err;
    r = pathlet_cli("info " + src("tests/engine/data/two_lines.vtk") + " --time-array tme");
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.err.find("no point array named 'tme' (did you mean 'time'?) (--time-array"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("LoadOptions"), std::string::npos) << r.err;
}

TEST(CliMistakes, ATimeOutsideTheDataIsAnErrorNamingItsSpanUnlessEmptyFramesAreAskedFor) {
    const std::string d = user_dir("time");
    for (const std::string t : {"50", "2:50:10", "-3"}) {
        SCOPED_TRACE(t);
        const CliRun r = in(d, "render --time " + t + kSmall);
        EXPECT_EQ(r.code, 2) << r.err;
        EXPECT_NE(r.err.find("error: --time "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("the data's time span, 0..4 s"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("--allow-empty-frames"), std::string::npos) << r.err;
        EXPECT_TRUE(entries(d).empty()) << "no output folder for a refused time";
    }
    CliRun r = in(d, "quality --time 40:41:0.5 --phantom small");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("0..4 s"), std::string::npos) << r.err;
    // bench the same, before any run or results folder (the class, not only render).
    r = in(d, "bench variant1_lineao --time 50 --phantom small --size 64x36 --frames 1 --warmup 0 --quiet --out b");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("the data's time span, 0..4 s"), std::string::npos) << r.err;
    if (fs::exists(d + "/b/results.json")) {  // bench leaves its (empty) results before the data is loaded
        std::ifstream in(d + "/b/results.json");
        EXPECT_TRUE(nlohmann::json::parse(in)["runs"].empty()) << "no run for a refused time";
    }
    r = in(d, "render --time 50 --allow-empty-frames" + std::string(kSmall));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(d + "/out/variant1_lineao/00000.png"));
    for (const char* cmd : {"render", "bench", "quality", "view"})
        EXPECT_NE(pathlet_cli(std::string(cmd) + " --help").out.find("--allow-empty-frames"), std::string::npos)
            << cmd << ": documented";
}

TEST(CliMistakes, AGraphWithoutANameIsNamedAfterItsFileAndAFolderSharedByTwoGraphsGetsANote) {
    const std::string d = user_dir("names");
    // The README's extending graph, as printed: no "name".
    write(d + "/fade_v1.json", R"({ "extends": "variant1_lineao",
  "passes": [ { "name": "gbuffer", "params": { "width_hook": "fade_width.geom" } } ] })");
    CliRun r = in(d, "render fade_v1.json --time 2" + std::string(kSmall));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("fade_v1 — 64x36"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(d + "/out/fade_v1/00000.png"));
    EXPECT_FALSE(fs::exists(d + "/out/variant1_lineao")) << "the base's folder is not the extending graph's";
    EXPECT_EQ(in(d, "graph fade_v1.json --plan").out.rfind("graph 'fade_v1' (fade_v1.json)", 0), 0u);
    // Two graph files of one name, in two folders: the second render into out/fig/ says so.
    fs::create_directories(d + "/a");
    fs::create_directories(d + "/b");
    write(d + "/a/fig.json", R"({"extends": "isl"})");
    write(d + "/b/fig.json", R"({"extends": "variant1_lineao"})");
    ASSERT_EQ(in(d, "render a/fig.json --time 2" + std::string(kSmall)).code, 0);
    r = in(d, "render a/fig.json --time 2" + std::string(kSmall));
    EXPECT_EQ(r.err.find("note: out/fig/"), std::string::npos) << "the same graph again: no note\n" << r.err;
    r = in(d, "render b/fig.json --time 2" + std::string(kSmall));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("note: out/fig/ holds frames of another graph, " + d + "/a/fig.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--out DIR"), std::string::npos) << r.err;
}

TEST(CliMistakes, AHooksCompileErrorNamesItsOwnFileAndLine) {
    const std::string d = user_dir("hook_error");
    write(d + "/my_fade.glsl", kWrongField);
    write(d + "/fade_v2.json", R"({"extends": "variant2_oit",
 "passes": [{"name": "fill_list", "params": {"color_hook": "my_fade.glsl"}}]})");
    const CliRun r = in(d, "render fade_v2.json --time 2" + std::string(kSmall));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(d + "/my_fade.glsl:4:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("agee"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("line_hooks.glsl:"), std::string::npos) << "a semantic error is the hook's, not the kit's\n" << r.err;
    EXPECT_FALSE(fs::exists(d + "/out")) << "nothing created before the inputs are known good";
}

TEST(CliMistakes, AHookNextToTheGraphWinsOverTheShippedOneOfItsName) {
    const std::string d = user_dir("shadow");
    // variant 3 names the shipped fade_width.geom; the user's own beside the graph is taken.
    write(d + "/fig.json", R"({"extends": "variant3_geomfade"})");
    write(d + "/fade_width.geom", "#include \"line_fade.glsl\"\nfloat line_width_hook(LinePoint p) { return 0.5 * ; }\n");
    CliRun r = in(d, "graph fig.json --plan");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("hook width_hook = fade_width.geom: " + d + "/fade_width.geom"), std::string::npos) << r.out;
    r = in(d, "render fig.json --time 2" + std::string(kSmall));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(d + "/fade_width.geom:2:"), std::string::npos) << "the user's file was compiled\n" << r.err;
    // The shipped graph, opened from elsewhere, keeps the shipped hook.
    r = pathlet_cli("graph variant3_geomfade --plan");
    EXPECT_EQ(r.out.find(d), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("/fade_width.geom"), std::string::npos) << r.out;
}

TEST(CliMistakes, ValidateReportsEveryErrorAndCompilesEveryHook) {
    const std::string d = user_dir("validate");
    write(d + "/my_fade.glsl", kWrongField);
    write(d + "/bad.json", R"({"extends": "variant1_lineao",
 "variables": {"radius2": {"type": "float", "default": "big"}},
 "passes": [{"name": "gbuffer", "params": {"windw": 3, "line_width": "$radius2"}},
            {"name": "lineao", "params": {"samples": 100000, "raduis": 2}},
            {"name": "extra", "type": "lineoa"}]})");
    CliRun r = in(d, "validate bad.json");
    EXPECT_EQ(r.code, 1) << r.err;
    for (const std::string want :
         {"bad.json:/variables/radius2/default: default of variable 'radius2' expects a number",
          "bad.json:/passes/0/params/windw: unknown parameter 'windw'", "did you mean 'window'",
          "bad.json:/passes/2/params/raduis: unknown parameter 'raduis'", "bad.json:/passes/2/params/samples: ",
          "/type: unknown pass type 'lineoa' (did you mean 'lineao'?)", "bad.json: 5 error(s)"})
        EXPECT_NE(r.err.find(want), std::string::npos) << want << "\n" << r.err;
    // A graph that is right but whose hook does not compile is not ok: its file and line.
    write(d + "/fade_v2.json", R"({"extends": "variant2_oit",
 "passes": [{"name": "fill_list", "params": {"color_hook": "my_fade.glsl"}}]})");
    r = in(d, "validate fade_v2.json variant2_oit");
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("fade_v2.json:/passes/1/params/color_hook: color_hook " + d + "/my_fade.glsl does not compile"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(d + "/my_fade.glsl:4:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("fade_v2.json: 1 error(s)"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("variant2_oit.json: ok"), std::string::npos) << "the shipped hooks compile\n" << r.out;
    EXPECT_EQ(in(d, "validate fade_v2.json --no-compile").code, 0) << "the text alone is right";
}

TEST(CliMistakes, AHooksParametersAreListedWithTypeDefaultRangeAndDoc) {
    const std::string d = user_dir("params");
    write(d + "/keep.glsl", R"(uniform float u_keep;  // @param 0.5 [0, 1] "how much of the opacity to keep"
vec4 line_color_hook(vec4 rgba, LinePoint p) { return vec4(rgba.rgb, rgba.a * u_keep); }
)");
    const std::string line = "keep (float, default 0.5, range [0, 1], from keep.glsl";
    CliRun r = in(d, "passes --describe fill_list --set color_hook=keep.glsl");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find(line), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("how much of the opacity to keep"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("tail_fade"), std::string::npos) << "the replaced default hook's parameters are not listed";
    r = in(d, "passes --describe fill_list --set colr_hook=keep.glsl");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("did you mean 'color_hook'"), std::string::npos) << r.err;
    write(d + "/fig.json", R"({"extends": "variant2_oit", "passes": [{"name": "fill_list",
      "params": {"color_hook": "keep.glsl", "keep": 0.25}}]})");
    r = in(d, "graph fig.json --params");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("keep = 0.25  (float, default 0.5, range [0, 1], from keep.glsl:1)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("(hook color_hook: " + d + "/keep.glsl)"), std::string::npos) << r.out;
}

// An option the chosen measure of `quality` ignores is an error naming it (the class of
// bench's ignored --out), before anything is loaded or rendered.
TEST(CliMistakes, AQualityOptionTheMeasureIgnoresIsAnError) {
    const std::string d = user_dir("quality_options");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"quality variant2_oit --transparency --rays 8", "--rays does nothing with --transparency"},
        {"quality variant2_oit --transparency --out q", "--out does nothing with --transparency"},
        {"quality variant1_lineao --focus-share 0.2", "--focus-share does nothing without --transparency"},
        {"quality variant2_wboit --reference variant2_exact --rays 8", "--rays does nothing with --reference"},
        {"quality variant2_wboit --reference variant2_exact --repeat 2", "--repeat does nothing with --reference"},
    };
    for (const auto& [cmd, text] : cases) {
        SCOPED_TRACE(cmd);
        const CliRun r = in(d, cmd + " --phantom small --size 32x18");
        EXPECT_EQ(r.code, 2) << r.err;
        EXPECT_NE(r.err.find(text), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("data:"), std::string::npos) << "refused before the data is loaded\n" << r.err;
    }
    EXPECT_TRUE(entries(d).empty()) << "nothing made";
}

// Every command's single-valued options, from its own --help: given twice, the usage error
// names the option and both values (the option declared once, in Args, for every command).
TEST(CliMistakes, EveryCommandRefusesASingleValuedOptionGivenTwice) {
    const CliRun top = pathlet_cli("--help");
    std::vector<std::string> commands;
    std::istringstream lines(top.out.substr(0, top.out.find("first steps:")));
    for (std::string l; std::getline(lines, l);)
        if (l.rfind("  ", 0) == 0 && l.size() > 2 && std::islower(static_cast<unsigned char>(l[2])))
            commands.push_back(l.substr(2, l.find(' ', 2) - 2));
    ASSERT_GE(commands.size(), 10u) << top.out;
    size_t checked = 0;
    for (const std::string& cmd : commands) {
        SCOPED_TRACE(cmd);
        const CliRun help = pathlet_cli(cmd + " --help");
        // "  --size WxH" or "  -o, --out DIR": a value, not "(repeatable)", not a flag.
        const std::regex valued(R"(^  (?:-\w, )?--([a-z-]+) [A-Z][^ ]*$)");
        std::istringstream h(help.out);
        std::string option;
        for (std::string l; option.empty() && std::getline(h, l);) {
            std::smatch m;
            if (std::regex_match(l, m, valued)) option = m[1];
        }
        if (option.empty()) continue;  // a command without single-valued options
        const CliRun r = pathlet_cli(cmd + " --" + option + " first --" + option + " second");
        EXPECT_EQ(r.code, 2) << r.err;
        EXPECT_NE(r.err.find("--" + option + " given twice: first and second"), std::string::npos) << r.err;
        ++checked;
    }
    EXPECT_GE(checked, 10u);
}
