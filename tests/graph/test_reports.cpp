#include "fake_registry.hpp"
#include "formats.hpp"

#include <algorithm>

#include <fstream>
#include <sstream>

using namespace pathlet;
using namespace pathlet::test;

namespace {

const char* kGraph = R"json({
  "name": "reports",
  "resources": {"taa_out": {"format": "rgba16f", "history": true}, "ldr": {"format": "rgba8"}},
  "passes": [
    {"name": "m0", "type": "mix"},
    {"name": "m1", "type": "mix", "inputs": {"a": "m0.dst"}},
    {"name": "m2", "type": "mix", "inputs": {"a": "m1.dst"}},
    {"name": "taa", "type": "taa", "inputs": {"current": "m2.dst", "history": "taa_out@prev"}, "outputs": {"resolved": "taa_out"}},
    {"name": "tonemap", "type": "tonemap", "params": {"exposure": 1}, "inputs": {"src": "taa_out"}, "outputs": {"dst": "ldr"}},
    {"name": "debug", "type": "blur", "inputs": {"src": "m1.dst"}}
  ],
  "outputs": [{"resource": "ldr", "capture": "out/{graph}/{frame:05}.png"}]
})json";

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(Reports, DotDrawsPassesResourcesCulledPassesAndHistoryEdges) {
    GraphFile g = parse(kGraph);
    CompiledGraph cg = compile_graph(g, fake_registry(), {32, 32});
    const std::string dot = graph_to_dot(cg, g);
    EXPECT_TRUE(contains(dot, "digraph \"reports\" {")) << dot;
    EXPECT_TRUE(contains(dot, "\"pass:taa\" [shape=box, label=\"taa\\n(taa)\"];")) << dot;
    EXPECT_TRUE(contains(dot, "\"res:m0.dst\" [shape=ellipse")) << dot;
    EXPECT_TRUE(contains(dot, "\"pass:m0\" -> \"res:m0.dst\" [label=\"dst\"];")) << dot;
    EXPECT_TRUE(contains(dot, "\"res:m0.dst\" -> \"pass:m1\" [label=\"a\"];")) << dot;
    EXPECT_TRUE(contains(dot, "\"res:taa_out\" -> \"pass:taa\" [style=dashed, label=\"history (@prev)\"];")) << dot;
    EXPECT_TRUE(contains(dot, "\"pass:debug\" [shape=box, style=dashed, color=grey, fontcolor=grey, label=\"debug\\n(culled)\", "
                              "tooltip=\"output debug.dst is never read and not captured\"];")) << dot;
    EXPECT_TRUE(contains(dot, "\"res:m1.dst\" -> \"pass:debug\" [color=grey, label=\"src\"];")) << dot;
    EXPECT_EQ(dot.back(), '\n');
    EXPECT_TRUE(contains(dot, "}\n"));
}

TEST(Reports, PlanShowsOrderLifetimesSlotsAndMemory) {
    CompiledGraph cg = compile(kGraph, {256, 256});
    const std::string plan = plan_to_text(cg);
    EXPECT_TRUE(contains(plan, "graph 'reports' (test.json), output 256x256\n")) << plan;
    EXPECT_TRUE(contains(plan, "execution order (5 passes):\n")) << plan;
    EXPECT_TRUE(contains(plan, "  0. m0 [mix]\n       out dst -> m0.dst\n")) << plan;
    EXPECT_TRUE(contains(plan, "       in  history <- taa_out@prev\n")) << plan;
    EXPECT_TRUE(contains(plan, "culled:\n  debug: output debug.dst is never read and not captured\n")) << plan;
    // Lifetime charts, one column per pass; resources listed by first use.
    EXPECT_TRUE(contains(plan, "  taa_out  |#####|  slot 0 ")) << plan;
    EXPECT_TRUE(contains(plan, "  m0.dst   |##...|  slot 1 ")) << plan;
    EXPECT_TRUE(contains(plan, "  m1.dst   |.##..|  slot 2 ")) << plan;
    EXPECT_TRUE(contains(plan, "  m2.dst   |..##.|  slot 1 ")) << plan;
    EXPECT_TRUE(contains(plan, "  ldr      |....#|  slot 3 ")) << plan;
    EXPECT_TRUE(contains(plan, "history")) << plan;
    EXPECT_TRUE(contains(plan, "  slot 1: 0.50 MiB <- m0.dst, m2.dst\n")) << plan;
    EXPECT_TRUE(contains(plan, "  slot 0: 1.00 MiB <- taa_out\n")) << plan;  // history: two copies
    // 3 x 0.5 MiB transients + 2 x 0.5 MiB history + 0.25 MiB ldr; pooling saves one transient.
    EXPECT_TRUE(contains(plan, "memory: 2.75 MiB before pooling, 2.25 MiB after pooling (saves 0.50 MiB, 18%)\n")) << plan;
}

TEST(Reports, PlanJsonHoldsTheSameFacts) {
    CompiledGraph cg = compile(kGraph, {32, 32});
    json j = plan_to_json(cg);
    EXPECT_EQ(j["name"], "reports");
    EXPECT_EQ(j["output_size"], json::array({32, 32}));
    ASSERT_EQ(j["passes"].size(), 5u);
    EXPECT_EQ(j["passes"][4]["name"], "tonemap");
    EXPECT_DOUBLE_EQ(j["passes"][4]["params"]["exposure"].get<double>(), 1.0);
    EXPECT_EQ(j["passes"][4]["params"]["operator"], "aces");
    EXPECT_EQ(j["passes"][3]["bindings"]["history"], json({{"resource", "taa_out"}, {"dir", "input"}, {"previous", true}}));
    EXPECT_EQ(j["culled"][0]["name"], "debug");
    EXPECT_EQ(j["resources"].size(), cg.resources.size());
    EXPECT_EQ(j["resources"][1]["name"], "m0.dst");
    EXPECT_EQ(j["resources"][1]["format"], "rgba16f");
    EXPECT_EQ(j["resources"][1]["writer"], "m0");
    EXPECT_EQ(j["resources"][1]["first_use"], 0);
    EXPECT_EQ(j["resources"][1]["last_use"], 1);
    EXPECT_EQ(j["resources"][0]["history"], true);
    EXPECT_EQ(j["slots"][1]["resources"], json::array({"m0.dst", "m2.dst"}));
    EXPECT_EQ(j["slots"][1]["format"], "rgba16f");
    EXPECT_EQ(j["memory"]["unpooled"], cg.memory_unpooled);
    EXPECT_EQ(j["memory"]["pooled"], cg.memory_pooled);
    EXPECT_EQ(j["outputs"][0]["capture"], "out/{graph}/{frame:05}.png");
}

TEST(Schema, ShippedSchemaDescribesTheFormat) {
    std::ifstream in(std::string(PATHLET_SOURCE_DIR) + "/graphs/schema/pathlet-graph.schema.json");
    ASSERT_TRUE(in.good());
    std::stringstream s;
    s << in.rdbuf();
    json schema = json::parse(s.str());
    EXPECT_EQ(schema["$schema"], "https://json-schema.org/draft/2020-12/schema");
    EXPECT_EQ(schema["additionalProperties"], false);
    for (const char* k : {"$schema", "version", "name", "description", "variables", "resources", "passes", "outputs", "extends"})
        EXPECT_TRUE(schema["properties"].contains(k)) << k;
    EXPECT_TRUE(schema["properties"]["description"].contains("description"));
    // The schema's format list is the engine's.
    json formats = schema["$defs"]["format"]["enum"];
    for (const auto& f : pathlet::format_names()) EXPECT_NE(std::find(formats.begin(), formats.end(), f), formats.end()) << f;
    EXPECT_EQ(formats.size(), pathlet::format_names().size());
}
