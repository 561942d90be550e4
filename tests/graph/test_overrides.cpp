#include "fake_registry.hpp"

using namespace pathlet;
using namespace pathlet::test;

namespace {

const char* kGraph = R"json({
  "variables": {
    "radius": {"type": "float", "default": 1.0, "min": 0, "max": 4},
    "use_ssao": {"type": "bool", "default": true},
    "op": {"type": "enum", "default": "aces", "choices": ["aces", "reinhard"]}
  },
  "passes": [
    {"name": "gbuffer", "type": "gbuffer"},
    {"name": "ssao", "type": "ssao", "enabled": "$use_ssao", "params": {"radius": "$radius"},
     "inputs": {"depth": "gbuffer.depth", "normal": "gbuffer.normal"}},
    {"name": "lighting", "type": "lighting",
     "inputs": {"depth": "gbuffer.depth", "normal": "gbuffer.normal", "albedo": "gbuffer.albedo", "ao": "ssao.ao"}},
    {"name": "tonemap", "type": "tonemap", "params": {"operator": "$op"}, "inputs": {"src": "lighting.color"}}
  ],
  "outputs": ["tonemap.dst"]
})json";

std::vector<Diagnostic> set(GraphFile& g, const std::vector<std::string>& sets) {
    std::vector<Diagnostic> d;
    apply_overrides(g, sets, fake_registry(), d);
    return d;
}

const CompiledPass& pass(const CompiledGraph& cg, const std::string& name) {
    for (const auto& p : cg.passes)
        if (p.name == name) return p;
    throw std::runtime_error("no pass " + name);
}

}  // namespace

TEST(Overrides, VariablesAndPassParameters) {
    GraphFile g = parse(kGraph);
    auto d = set(g, {"radius=2.5", "tonemap.exposure=1.5", "ssao.tint=#ff0000", "ssao.samples=8", "op=reinhard"});
    ASSERT_TRUE(d.empty()) << all(d);
    CompiledGraph cg = compile_graph(g, fake_registry(), {64, 64});
    EXPECT_DOUBLE_EQ(pass(cg, "ssao").params["radius"].get<double>(), 2.5);   // through $radius
    EXPECT_EQ(pass(cg, "ssao").params["samples"], 8);
    EXPECT_EQ(pass(cg, "ssao").params["tint"], json::array({1.0, 0.0, 0.0}));
    EXPECT_EQ(pass(cg, "ssao").params["mode"], "hemisphere");                 // default
    EXPECT_DOUBLE_EQ(pass(cg, "tonemap").params["exposure"].get<double>(), 1.5);
    EXPECT_EQ(pass(cg, "tonemap").params["operator"], "reinhard");
    EXPECT_DOUBLE_EQ(cg.variables["radius"].get<double>(), 2.5);
}

TEST(Overrides, LaterSetsWin) {
    GraphFile g = parse(kGraph);
    ASSERT_TRUE(set(g, {"radius=2", "radius=3"}).empty());
    EXPECT_DOUBLE_EQ(g.variables[1].value.get<double>(), 3.0);
}

TEST(Overrides, BadValuesAndNames) {
    GraphFile g = parse(kGraph);
    auto d = set(g, {"radius=abc", "radius=9", "raduis=1", "tonemp.exposure=1", "tonemap.exposur=1", "noequals",
                     "tonemap.operator=acse", "use_ssao=maybe", "ssao.enabled=perhaps"});
    EXPECT_TRUE(has_problem(d, "/variables/radius", "--set radius=abc: variable 'radius' cannot read 'abc' as float"));
    EXPECT_TRUE(has_problem(d, "/variables/radius", "--set radius=9: variable 'radius' value 9 is out of range"));
    EXPECT_TRUE(has_problem(d, "/variables", "unknown variable 'raduis' (did you mean 'radius'?)"));
    EXPECT_TRUE(has_problem(d, "/passes", "unknown pass 'tonemp' (did you mean 'tonemap'?)"));
    EXPECT_TRUE(has_problem(d, "/passes/3/params", "unknown parameter 'exposur' for pass type 'tonemap' (did you mean 'exposure'?)"));
    EXPECT_TRUE(has_problem(d, "", "--set noequals: expected name=value"));
    EXPECT_TRUE(has_problem(d, "/passes/3/params/operator", "'acse' is not one of aces, reinhard"));
    EXPECT_TRUE(has_problem(d, "/variables/use_ssao", "--set use_ssao=maybe"));
    EXPECT_TRUE(has_problem(d, "/passes/1/enabled", "enabled must be true or false"));
    EXPECT_EQ(d.size(), 9u) << all(d);
    EXPECT_DOUBLE_EQ(g.variables[1].value.get<double>(), 1.0);  // bad values change nothing
}

TEST(Overrides, DisablingAPassThroughItsVariable) {
    GraphFile g = parse(kGraph);
    ASSERT_TRUE(set(g, {"use_ssao=false"}).empty());
    CompiledGraph cg = compile_graph(g, fake_registry(), {64, 64});
    ASSERT_EQ(cg.culled.size(), 1u);
    EXPECT_EQ(cg.culled[0].name, "ssao");
    EXPECT_EQ(cg.culled[0].reason, "disabled");
    EXPECT_EQ(pass(cg, "lighting").bindings.count("ao"), 0u);  // optional input left unbound
    EXPECT_EQ(cg.find_resource("ssao.ao"), -1);
}

TEST(Overrides, DisablingAPassDirectly) {
    GraphFile g = parse(kGraph);
    ASSERT_TRUE(set(g, {"ssao.enabled=off"}).empty());
    CompiledGraph cg = compile_graph(g, fake_registry(), {64, 64});
    ASSERT_EQ(cg.culled.size(), 1u);
    EXPECT_EQ(cg.culled[0].reason, "disabled");
}
