// Graphs that extend graphs (graph_extends.cpp): the merge rules, errors that point into the
// merged document, cycles, unknown bases, changes to passes the base does not have, and
// "--set pass.type=TYPE".
#include "fake_registry.hpp"

#include <filesystem>
#include <fstream>

#include <unistd.h>

using namespace pathlet;
using namespace pathlet::test;
namespace fs = std::filesystem;

namespace {

const std::string& dir() {
    static const std::string d = [] {
        fs::path p = fs::temp_directory_path() / ("pathlet_extends_" + std::to_string(::getpid()));
        fs::create_directories(p / "sub");
        return p.string();
    }();
    return d;
}
std::string write(const std::string& name, const std::string& text) {
    const std::string p = dir() + "/" + name;
    std::ofstream(p) << text;
    return p;
}

const char* kBase = R"({
  "version": 1, "name": "base", "description": "the base",
  "plugin_dirs": ["plugins"],
  "variables": {"radius": {"type": "float", "default": 0.5, "min": 0, "max": 4, "doc": "AO radius"},
                "exposure": {"type": "float", "default": 0, "min": -10, "max": 10}},
  "resources": {"ao": {"format": "r8"}},
  "passes": [
    {"name": "g", "type": "gbuffer"},
    {"name": "ao", "type": "ssao", "params": {"radius": "$radius", "samples": 8},
     "inputs": {"depth": "g.depth", "normal": "g.normal"}, "outputs": {"ao": "ao"}},
    {"name": "light", "type": "lighting",
     "inputs": {"depth": "g.depth", "normal": "g.normal", "albedo": "g.albedo", "ao": "ao"}},
    {"name": "tm", "type": "tonemap", "params": {"exposure": "$exposure"}, "inputs": {"src": "light.color"}}
  ],
  "outputs": [{"resource": "tm.dst", "capture": "{out}/base_{frame:05}.png"}]
})";

GraphFile parse_file(const std::string& path) { return parse_graph_file(path); }

std::vector<Diagnostic> file_problems(const std::string& path) {
    try {
        GraphFile g = parse_graph_file(path);
        return validate_graph(g, fake_registry());
    } catch (const GraphError& e) {
        return e.diagnostics;
    }
}

}  // namespace

TEST(Extends, ChangesMergeIntoTheBase) {
    write("base.json", kBase);
    const std::string path = write("derived.json", R"({
      "extends": "base.json", "name": "derived",
      "variables": {"radius": {"default": 2}, "new_var": {"type": "bool", "default": true}, "exposure": null},
      "passes": [
        {"name": "ao", "params": {"samples": 32, "mode": "sphere"}},
        {"name": "tm", "params": {"exposure": 1.5}, "type": "tonemap"},
        {"name": "soft", "type": "blur", "inputs": {"src": "ao"}},
        {"name": "light", "inputs": {"ao": null}}
      ],
      "outputs": [{"resource": "tm.dst"}, {"resource": "soft.dst"}]
    })");
    GraphFile g = parse_file(path);
    EXPECT_EQ(g.name, "derived");
    EXPECT_EQ(g.description, "the base");
    ASSERT_EQ(g.passes.size(), 5u);
    EXPECT_EQ(g.passes[1].params["samples"], 32);            // replaced
    EXPECT_EQ(g.passes[1].params["radius"], "$radius");      // kept
    EXPECT_EQ(g.passes[1].params["mode"], "sphere");         // added
    EXPECT_EQ(g.passes[3].params["exposure"], 1.5);
    EXPECT_FALSE(g.passes[2].inputs.count("ao"));            // null removes a binding
    EXPECT_EQ(g.passes[4].name, "soft");                     // a new pass comes last
    ASSERT_EQ(g.variables.size(), 2u);                       // exposure removed, new_var added
    EXPECT_EQ(g.variables[1].name, "radius");
    EXPECT_EQ(g.variables[1].value, 2.0);
    EXPECT_EQ(g.variables[1].decl.doc, "AO radius");         // the rest of the entry stays
    ASSERT_EQ(g.outputs.size(), 2u);                         // outputs replace the base's
    // The base's plugin folder stays relative to the base's file; both folders are searched for hooks.
    ASSERT_EQ(g.plugin_dirs.size(), 1u);
    EXPECT_EQ(g.plugin_dirs[0], (fs::path(dir()) / "plugins").lexically_normal().string());
    ASSERT_EQ(g.extends.size(), 1u);
    EXPECT_NE(g.extends[0].find("base.json"), std::string::npos);
    // The merged graph is whole: tm no longer names the removed "$exposure".
    EXPECT_TRUE(file_problems(path).empty()) << all(file_problems(path));
}

TEST(Extends, ErrorsPointIntoTheMergedGraph) {
    write("base.json", kBase);
    const std::string path = write("bad_value.json", R"({"extends": "base.json",
      "passes": [{"name": "ao", "params": {"samples": 1000}}]})");
    auto d = file_problems(path);
    ASSERT_EQ(d.size(), 1u) << all(d);
    EXPECT_NE(d[0].str().find("bad_value.json:/passes/1/params/samples: parameter 'samples' value 1000 is out of range"),
              std::string::npos)
        << d[0].str();
    // The merged document the pointers refer to.
    json merged = expanded_graph_json(path);
    EXPECT_EQ(merged["/passes/1/params/samples"_json_pointer], 1000);
    EXPECT_FALSE(merged.contains("extends"));
}

TEST(Extends, BasesExtendBasesAndACycleIsNamed) {
    write("base.json", kBase);
    write("mid.json", R"({"extends": "base.json", "passes": [{"name": "ao", "params": {"samples": 12}}]})");
    GraphFile g = parse_file(write("top.json", R"({"extends": "mid.json", "passes": [{"name": "tm", "enabled": false}]})"));
    EXPECT_EQ(g.passes[1].params["samples"], 12);
    EXPECT_EQ(g.passes[3].enabled, false);
    EXPECT_EQ(g.extends.size(), 2u);

    write("a.json", R"({"extends": "b.json"})");
    write("b.json", R"({"extends": "sub/../a.json"})");
    auto d = file_problems(dir() + "/a.json");
    ASSERT_FALSE(d.empty());
    EXPECT_NE(d[0].message.find("extends forms a cycle"), std::string::npos) << d[0].str();
    EXPECT_NE(d[0].message.find("b.json"), std::string::npos) << d[0].str();
    write("self.json", R"({"extends": "self.json"})");
    d = file_problems(dir() + "/self.json");
    ASSERT_FALSE(d.empty());
    EXPECT_NE(d[0].message.find("cycle"), std::string::npos) << d[0].str();
}

TEST(Extends, AnUnknownBaseIsAnErrorWithTheShippedNames) {
    auto d = file_problems(write("unknown.json", R"({"extends": "variant1_lineoa"})"));
    ASSERT_FALSE(d.empty());
    EXPECT_EQ(d[0].pointer, "/extends");
    EXPECT_NE(d[0].message.find("unknown base graph 'variant1_lineoa'"), std::string::npos) << d[0].str();
    EXPECT_NE(d[0].message.find("did you mean 'variant1_lineao'"), std::string::npos) << d[0].str();
    d = file_problems(write("missing.json", R"({"extends": "sub/nothing.json"})"));
    ASSERT_FALSE(d.empty());
    EXPECT_NE(d[0].message.find("base graph 'sub/nothing.json' not found"), std::string::npos) << d[0].str();
    d = file_problems(write("not_json.json", R"({"extends": "/etc/passwd"})"));
    ASSERT_FALSE(d.empty());
    EXPECT_NE(d[0].message.find("a .json file or the name of a shipped graph"), std::string::npos) << d[0].str();
    d = file_problems(write("typed.json", R"({"extends": 3})"));
    ASSERT_FALSE(d.empty());
    EXPECT_NE(d[0].message.find("extends must name a base graph"), std::string::npos) << d[0].str();
}

TEST(Extends, ChangingAPassTheBaseDoesNotHaveIsAnError) {
    write("base.json", kBase);
    auto d = file_problems(write("typo.json", R"({"extends": "base.json", "passes": [{"name": "a0", "params": {"samples": 4}}]})"));
    ASSERT_FALSE(d.empty());
    EXPECT_EQ(d[0].pointer, "/passes/0/name");
    EXPECT_NE(d[0].message.find("no pass 'a0' in the base graph to change"), std::string::npos) << d[0].str();
    EXPECT_NE(d[0].message.find("did you mean 'ao'"), std::string::npos) << d[0].str();
    EXPECT_NE(d[0].message.find("a new pass needs a \"type\""), std::string::npos) << d[0].str();
    d = file_problems(write("remove.json", R"({"extends": "base.json", "passes": [{"name": "nope", "remove": true}]})"));
    ASSERT_FALSE(d.empty());
    EXPECT_NE(d[0].message.find("no pass 'nope' in the base graph to remove"), std::string::npos) << d[0].str();
}

TEST(Extends, RemovingAPassAndReplacingItsType) {
    write("base.json", kBase);
    GraphFile g = parse_file(write("swap.json", R"({"extends": "base.json", "passes": [
        {"name": "ao", "remove": true}, {"name": "light", "inputs": {"ao": null}},
        {"name": "tm", "type": "blur", "params": {"exposure": null, "taps": 3}}]})"));
    ASSERT_EQ(g.passes.size(), 3u);
    EXPECT_EQ(g.passes[2].type, "blur");
    EXPECT_FALSE(g.passes[2].params.contains("exposure"));
    auto d = validate_graph(g, fake_registry());
    // tm.dst is blur's output too: the merged graph is whole.
    EXPECT_TRUE(d.empty()) << all(d);
}

TEST(Overrides, SetPassTypeReplacesTheType) {
    GraphFile g = parse(R"({"passes": [{"name": "p", "type": "tonemap", "inputs": {"src": "x"}},
                                      {"name": "x0", "type": "anyout", "outputs": {"dst": "x"}}],
                          "resources": {"x": {"format": "rgba16f"}}, "outputs": ["p.dst"]})");
    std::vector<Diagnostic> d;
    apply_overrides(g, {"p.type=blur", "p.taps=3"}, fake_registry(), d);
    EXPECT_TRUE(d.empty()) << all(d);
    EXPECT_EQ(g.passes[0].type, "blur");
    EXPECT_EQ(g.passes[0].params["taps"], 3);  // the new type's parameter, in the same run
    apply_overrides(g, {"p.type=blurr"}, fake_registry(), d);
    EXPECT_TRUE(has_problem(d, "/passes/0/type", "unknown pass type 'blurr'")) << all(d);
    EXPECT_NE(d.back().message.find("did you mean 'blur'"), std::string::npos) << all(d);
}

// "extends" as a list: each later base merges over the ones before it, then the file over all.
TEST(Extends, ListedBasesMergeInOrderThenTheFile) {
    write("base.json", kBase);
    write("part.json", R"({"variables": {"radius": {"default": 1}},
      "passes": [{"name": "ao", "params": {"samples": 12, "mode": "sphere"}},
                 {"name": "soft", "type": "blur", "inputs": {"src": "ao"}}]})");
    const std::string path = write("listed.json", R"({"extends": ["base.json", "part.json"],
      "passes": [{"name": "ao", "params": {"samples": 20}}]})");
    GraphFile g = parse_file(path);
    ASSERT_EQ(g.passes.size(), 5u);
    EXPECT_EQ(g.passes[4].name, "soft");                  // the later base's new pass after the first's
    EXPECT_EQ(g.passes[1].params["samples"], 20);         // the file over both
    EXPECT_EQ(g.passes[1].params["mode"], "sphere");      // the later base over the first
    EXPECT_EQ(g.passes[1].params["radius"], "$radius");   // the first base's
    EXPECT_EQ(g.variables[1].value, 1.0);
    ASSERT_EQ(g.extends.size(), 2u);
    EXPECT_NE(g.extends[1].find("part.json"), std::string::npos);
    EXPECT_TRUE(file_problems(path).empty()) << all(file_problems(path));

    auto d = file_problems(write("listed_bad.json", R"({"extends": ["base.json", 3]})"));
    ASSERT_FALSE(d.empty());
    EXPECT_EQ(d[0].pointer, "/extends/1");
    EXPECT_NE(d[0].message.find("extends must name a base graph"), std::string::npos) << d[0].str();
    d = file_problems(write("listed_empty.json", R"({"extends": []})"));
    ASSERT_FALSE(d.empty());
    EXPECT_EQ(d[0].pointer, "/extends");
    d = file_problems(write("listed_missing.json", R"({"extends": ["base.json", "sub/nothing.json"]})"));
    ASSERT_FALSE(d.empty());
    EXPECT_EQ(d[0].pointer, "/extends/1");
    EXPECT_NE(d[0].message.find("base graph 'sub/nothing.json' not found"), std::string::npos) << d[0].str();
}

// Shipped bases (graphs/base/) are found by name from anywhere, and named when one is mistyped.
TEST(Extends, AShippedBaseIsFoundByName) {
    json merged = expanded_graph_json(write("on_lines.json", R"({"extends": "base/lines"})"));
    ASSERT_TRUE(merged.contains("passes"));
    EXPECT_EQ(merged["passes"][0]["name"], "wall");
    EXPECT_TRUE(merged["variables"].contains("window"));
    auto d = file_problems(write("base_typo.json", R"({"extends": "base/line"})"));
    ASSERT_FALSE(d.empty());
    EXPECT_NE(d[0].message.find("unknown base graph 'base/line'"), std::string::npos) << d[0].str();
    EXPECT_NE(d[0].message.find("did you mean 'base/lines'"), std::string::npos) << d[0].str();
    EXPECT_NE(d[0].message.find("shipped bases: "), std::string::npos) << d[0].str();
    d = file_problems(write("base_up.json", R"({"extends": "base/../variant2_oit"})"));
    ASSERT_FALSE(d.empty());
    EXPECT_NE(d[0].message.find("a .json file or the name of a shipped graph"), std::string::npos) << d[0].str();
}

const char* kSetBase = R"({
  "version": 1,
  "variables": {"radius": {"type": "float", "default": 0.5, "min": 0, "max": 4}},
  "param_sets": {"common": {"radius": "$radius", "samples": 8}},
  "resources": {"ao": {"format": "r8"}},
  "passes": [
    {"name": "g", "type": "gbuffer"},
    {"name": "ao", "type": "ssao", "param_set": "common",
     "inputs": {"depth": "g.depth", "normal": "g.normal"}, "outputs": {"ao": "ao"}},
    {"name": "light", "type": "lighting",
     "inputs": {"depth": "g.depth", "normal": "g.normal", "albedo": "g.albedo", "ao": "ao"}}
  ],
  "outputs": [{"resource": "light.color"}]
})";

// A param set fills the passes that name it, their own params over it, in the merged graph:
// an extending file's change to the set reaches the base's passes too.
TEST(Extends, ParamSetsFillThePassesThatNameThem) {
    write("set_base.json", kSetBase);
    GraphFile plain = parse_file(dir() + "/set_base.json");
    EXPECT_EQ(plain.passes[1].params, json({{"radius", "$radius"}, {"samples", 8}}));
    const std::string path = write("set_top.json", R"({"extends": "set_base.json",
      "param_sets": {"common": {"samples": 16}},
      "passes": [{"name": "ao2", "type": "ssao", "param_set": "common", "params": {"radius": null, "mode": "sphere"},
                  "inputs": {"depth": "g.depth", "normal": "g.normal"}}]})");
    GraphFile g = parse_file(path);
    EXPECT_EQ(g.passes[1].params, json({{"radius", "$radius"}, {"samples", 16}}));
    EXPECT_EQ(g.passes[3].params, json({{"mode", "sphere"}, {"samples", 16}}));  // null leaves the set's radius out
    json merged = expanded_graph_json(path);
    EXPECT_FALSE(merged.contains("param_sets"));
    for (const auto& p : merged["passes"]) EXPECT_FALSE(p.contains("param_set")) << p.dump();
    EXPECT_TRUE(file_problems(path).empty()) << all(file_problems(path));
}

TEST(Extends, ParamSetMistakesAreNamedWithTheirPlace) {
    write("set_base.json", kSetBase);
    auto d = file_problems(write("set_typo.json", R"({"extends": "set_base.json",
      "passes": [{"name": "ao", "param_set": "comon"}]})"));
    ASSERT_EQ(d.size(), 1u) << all(d);
    EXPECT_EQ(d[0].pointer, "/passes/1/param_set");
    EXPECT_NE(d[0].str().find("set_typo.json:/passes/1/param_set: unknown param set 'comon'"), std::string::npos) << d[0].str();
    EXPECT_NE(d[0].message.find("did you mean 'common'"), std::string::npos) << d[0].str();
    d = file_problems(write("set_none.json", R"({"version": 1, "passes": [{"name": "g", "type": "gbuffer", "param_set": "lines"}],
      "outputs": [{"resource": "g.albedo"}]})"));
    ASSERT_EQ(d.size(), 1u) << all(d);
    EXPECT_NE(d[0].message.find("the graph's param sets: none"), std::string::npos) << d[0].str();
    d = file_problems(write("set_list.json", R"({"extends": "set_base.json", "param_sets": ["common"]})"));
    ASSERT_FALSE(d.empty());
    EXPECT_EQ(d[0].pointer, "/param_sets");
    d = file_problems(write("set_number.json", R"({"extends": "set_base.json", "param_sets": {"more": 3}})"));
    ASSERT_FALSE(d.empty());
    EXPECT_EQ(d[0].pointer, "/param_sets/more");
    EXPECT_NE(d[0].message.find("a param set is an object of parameters"), std::string::npos) << d[0].str();
}
