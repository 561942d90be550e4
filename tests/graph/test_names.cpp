// Issue 41: a graph's name is its own (a graph without "name" is named after its file, never
// after the base it extends), a graph argument that names nothing is one did-you-mean before
// anything is done, and a file with a wrong part still has every other error reported.
#include "fake_registry.hpp"
#include "plugin_host.hpp"

#include <filesystem>
#include <fstream>

#include <unistd.h>

using namespace pathlet;
using namespace pathlet::test;
namespace fs = std::filesystem;

namespace {

const std::string& dir() {
    static const std::string d = [] {
        fs::path p = fs::temp_directory_path() / ("pathlet_names_" + std::to_string(::getpid()));
        fs::create_directories(p);
        return p.string();
    }();
    return d;
}
std::string write(const std::string& name, const std::string& text) {
    const std::string p = dir() + "/" + name;
    std::ofstream(p) << text;
    return p;
}

const char* kBase = R"({"name": "the_base",
  "passes": [{"name": "g", "type": "gbuffer"},
             {"name": "tm", "type": "tonemap", "inputs": {"src": "g.albedo"}}],
  "outputs": [{"resource": "tm.dst", "capture": "{out}/{graph}/{frame:05}.png"}]})";

}  // namespace

TEST(Names, AGraphWithoutANameIsNamedAfterItsFileNotItsBase) {
    write("named_base.json", kBase);
    const std::string fade = write("fade_v1.json", R"({"extends": "named_base.json"})");
    EXPECT_EQ(parse_graph_file(fade).name, "fade_v1");
    EXPECT_EQ(compile_graph(parse_graph_file(fade), fake_registry(), {64, 36}).name, "fade_v1") << "{graph} and --plan";
    EXPECT_EQ(parse_graph_file(dir() + "/named_base.json").name, "the_base");
    // A name of its own wins; so does the file name of a graph that extends nothing.
    EXPECT_EQ(parse_graph_file(write("own.json", R"({"extends": "named_base.json", "name": "mine"})")).name, "mine");
    EXPECT_EQ(parse_graph_file(write("plain.json", R"({"passes": [], "outputs": []})")).name, "plain");
    // --expanded, the merged document, has no name the file did not give.
    EXPECT_FALSE(expanded_graph_json(fade).contains("name"));
}

// A graph's name names its folder in output paths ({graph}, quality --out, the output-folder
// record): a downloaded graph must not reach outside them through it.
TEST(Names, AGraphNameThatCouldNameAnotherFolderIsAnErrorAtItsPlace) {
    const std::string control = std::string("bell") + char(7);
    for (const std::string& bad : {std::string("../escape"), std::string("a/b"), std::string(".."),
                                   std::string("x\\y"), control}) {
        const std::string path = write("bad_name.json", "{\"name\": " + nlohmann::json(bad).dump() +
                                                            ", \"passes\": [], \"outputs\": []}");
        try {
            parse_graph_file(path);
            ADD_FAILURE() << "graph name '" << bad << "' accepted";
        } catch (const GraphError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find(path + ":/name: graph name"), std::string::npos) << m;
        }
    }
    // A file name standing in for a missing "name" is held to the same rule.
    const std::string dots = write("...json", R"({"passes": [], "outputs": []})");
    EXPECT_THROW(parse_graph_file(dots), GraphError) << "a file '...json' would be named '..'";
    // Dots inside a name are fine, and so is every shipped graph's.
    EXPECT_EQ(parse_graph_file(write("dotted.json", R"({"name": "fade.v2", "passes": [], "outputs": []})")).name, "fade.v2");
}

TEST(Names, AnUnknownGraphIsOneLineWithTheClosestName) {
    try {
        find_graph_file("variant1_lineoa");
        FAIL() << "no such graph";
    } catch (const GraphNotFound& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        EXPECT_NE(m.find("no graph 'variant1_lineoa'"), std::string::npos) << m;
        EXPECT_NE(m.find("(did you mean 'variant1_lineao'?)"), std::string::npos) << m;
        EXPECT_NE(m.find("shipped graphs: "), std::string::npos) << m;
    }
    // A file of the user's folder, misspelt: the closest .json file there.
    write("figure_one.json", kBase);
    try {
        find_graph_file(dir() + "/figure_onw.json");
        FAIL() << "no such file";
    } catch (const GraphNotFound& e) {
        EXPECT_NE(std::string(e.what()).find("did you mean '" + dir() + "/figure_one.json'?"), std::string::npos) << e.what();
    }
    EXPECT_EQ(find_graph_file(dir() + "/figure_one.json"), dir() + "/figure_one.json");
    EXPECT_EQ(fs::path(find_graph_file("isl")).filename(), "isl.json");
    EXPECT_EQ(fs::path(find_graph_file("isl.json")).filename(), "isl.json");
}

TEST(Names, AWrongVariableDefaultHidesNoOtherError) {
    const std::string f = write("many_errors.json", R"({
      "variables": {"radius": {"type": "float", "default": "big"}, "on": {"type": "bool", "default": 3}},
      "passes": [{"name": "g", "type": "gbuffer", "enabled": "$on"},
                 {"name": "ao", "type": "ssao", "params": {"radius": "$radius", "samplez": 8},
                  "inputs": {"depth": "g.depth", "normal": "g.normal"}},
                 {"name": "tm", "type": "tonemapp", "inputs": {"src": "ao.ao"}}],
      "outputs": [{"resource": "tm.dst"}]})");
    EXPECT_THROW(parse_graph_file(f), GraphError) << "the strict parse still refuses it";
    std::vector<Diagnostic> d;
    const GraphFile g = parse_graph_file(f, d);
    const auto more = validate_graph(g, fake_registry());
    d.insert(d.end(), more.begin(), more.end());
    auto has = [&](const std::string& pointer, const std::string& phrase) {
        for (const auto& x : d)
            if (x.file == f && x.pointer == pointer && x.message.find(phrase) != std::string::npos) return true;
        return false;
    };
    EXPECT_TRUE(has("/variables/radius/default", "expects a number")) << all(d);
    EXPECT_TRUE(has("/variables/on/default", "expects a bool")) << all(d);
    EXPECT_TRUE(has("/passes/1/params/samplez", "did you mean 'samples'")) << all(d);
    EXPECT_TRUE(has("/passes/2/type", "did you mean 'tonemap'")) << all(d);
    EXPECT_EQ(d.size(), 4u) << "a broken variable's users are not errors of their own:\n" << all(d);
}
