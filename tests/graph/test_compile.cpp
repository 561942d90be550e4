#include "fake_registry.hpp"

using namespace pathlet;
using namespace pathlet::test;

namespace {

std::vector<std::string> order(const CompiledGraph& cg) {
    std::vector<std::string> v;
    for (const auto& p : cg.passes) v.push_back(p.name);
    return v;
}

const CompiledResource& res(const CompiledGraph& cg, const std::string& name) {
    int i = cg.find_resource(name);
    if (i < 0) throw std::runtime_error("no resource " + name);
    return cg.resources[i];
}

std::string reason(const CompiledGraph& cg, const std::string& pass) {
    for (const auto& c : cg.culled)
        if (c.name == pass) return c.reason;
    return "(not culled)";
}

const char* kDeferred = R"json({
  "name": "deferred",
  "variables": {"use_ssao": {"type": "bool", "default": true}, "r": {"type": "int", "default": 2},
                "m": {"type": "string", "default": "sphere"}},
  "resources": {"hdr": {"format": "rgba16f"}, "ldr": {"format": "rgba8"}},
  "passes": [
    {"name": "gbuffer", "type": "gbuffer"},
    {"name": "ssao", "type": "ssao", "enabled": "$use_ssao", "params": {"radius": "$r", "mode": "$m"},
     "inputs": {"depth": "gbuffer.depth", "normal": "gbuffer.normal"}},
    {"name": "lighting", "type": "lighting",
     "inputs": {"depth": "gbuffer.depth", "normal": "gbuffer.normal", "albedo": "gbuffer.albedo", "ao": "ssao.ao"},
     "outputs": {"color": "hdr"}},
    {"name": "debug", "type": "blur", "inputs": {"src": "gbuffer.normal"}},
    {"name": "debug2", "type": "blur", "inputs": {"src": "debug.dst"}},
    {"name": "tonemap", "type": "tonemap", "inputs": {"src": "hdr"}, "outputs": {"dst": "ldr"}}
  ],
  "outputs": [{"resource": "ldr", "capture": "out/{graph}/{frame:05}.png"}]
})json";

}  // namespace

TEST(Compile, DeferredGraph) {
    CompiledGraph cg = compile(kDeferred);
    EXPECT_EQ(order(cg), (std::vector<std::string>{"gbuffer", "ssao", "lighting", "tonemap"}));
    EXPECT_EQ(cg.name, "deferred");
    EXPECT_EQ(cg.file, "test.json");
    EXPECT_EQ(cg.output_size, glm::ivec2(1920, 1080));
    // $variable substitution: an int variable feeds a float parameter, a string one an enum.
    EXPECT_DOUBLE_EQ(cg.passes[1].params["radius"].get<double>(), 2.0);
    EXPECT_EQ(cg.passes[1].params["mode"], "sphere");
    EXPECT_EQ(cg.passes[1].params["samples"], 16);
    EXPECT_EQ(cg.variables, json({{"use_ssao", true}, {"r", 2}, {"m", "sphere"}}));
    // Implicit resources take format and size from their pins.
    EXPECT_EQ(res(cg, "gbuffer.depth").format, "depth32f");
    EXPECT_EQ(res(cg, "gbuffer.depth").internal_format, GLenum(GL_DEPTH_COMPONENT32F));
    EXPECT_EQ(res(cg, "ssao.ao").format, "r8");
    EXPECT_EQ(res(cg, "ssao.ao").width, 960);
    EXPECT_EQ(res(cg, "ssao.ao").height, 540);
    EXPECT_EQ(res(cg, "hdr").bytes, size_t(1920) * 1080 * 8);
    // Bindings and writers.
    const CompiledPass& lighting = cg.passes[2];
    EXPECT_EQ(cg.resources[lighting.bindings.at("ao").resource].name, "ssao.ao");
    EXPECT_EQ(cg.resources[lighting.bindings.at("color").resource].name, "hdr");
    EXPECT_EQ(res(cg, "hdr").writer, 2);
    EXPECT_EQ(lighting.type->type, "lighting");
    EXPECT_EQ(lighting.pointer, "/passes/2");
    ASSERT_EQ(cg.outputs.size(), 1u);
    EXPECT_EQ(cg.outputs[0].resource, "ldr");
    EXPECT_TRUE(res(cg, "ldr").captured);
}

TEST(Compile, CulledPassesSayWhy) {
    CompiledGraph cg = compile(kDeferred);
    ASSERT_EQ(cg.culled.size(), 2u);
    EXPECT_EQ(reason(cg, "debug"), "output debug.dst is read only by culled passes (debug2)");
    EXPECT_EQ(reason(cg, "debug2"), "output debug2.dst is never read and not captured");
    EXPECT_EQ(cg.find_resource("debug.dst"), -1);  // resources of culled passes are not allocated
}

TEST(Compile, CullReasonListsEveryOutput) {
    CompiledGraph cg = compile(R"json({"passes": [{"name": "g", "type": "gbuffer"}, {"name": "m", "type": "mix"}],
                                       "outputs": ["m.dst"]})json");
    EXPECT_EQ(reason(cg, "g"), "outputs g.depth, g.normal, g.albedo are never read and not captured");
}

TEST(Compile, DisabledPassViaVariable) {
    std::string text = kDeferred;
    text.replace(text.find("\"default\": true"), 15, "\"default\": false");
    CompiledGraph cg = compile(text);
    EXPECT_EQ(reason(cg, "ssao"), "disabled");
    EXPECT_EQ(order(cg), (std::vector<std::string>{"gbuffer", "lighting", "tonemap"}));
    EXPECT_EQ(cg.passes[1].bindings.count("ao"), 0u);
    EXPECT_EQ(cg.variables["use_ssao"], false);
}

TEST(Compile, DisabledWriterOfARequiredInputIsAnError) {
    try {
        compile(R"json({"passes": [{"name": "a", "type": "mix", "enabled": false},
                                   {"name": "b", "type": "blur", "inputs": {"src": "a.dst"}},
                                   {"name": "c", "type": "mix", "enabled": false}],
                        "outputs": ["b.dst", "c.dst"]})json");
        FAIL() << "compiled";
    } catch (const GraphError& e) {
        EXPECT_TRUE(has_problem(e.diagnostics, "/passes/1/inputs/src", "its writer 'a' is disabled"));
        EXPECT_TRUE(has_problem(e.diagnostics, "/outputs/1/resource", "written by pass 'c', which is disabled"));
    }
}

TEST(Compile, TopologicalOrderKeepsFileOrderAmongTies) {
    CompiledGraph cg = compile(R"json({"passes": [
        {"name": "late", "type": "mix", "inputs": {"a": "src.dst", "b": "x.dst"}},
        {"name": "x", "type": "mix"},
        {"name": "src", "type": "mix"},
        {"name": "y", "type": "mix"},
        {"name": "final", "type": "mix", "inputs": {"a": "late.dst", "b": "y.dst"}}
      ], "outputs": ["final.dst"]})json");
    EXPECT_EQ(order(cg), (std::vector<std::string>{"x", "src", "late", "y", "final"}));
    // Every read comes after its write.
    for (size_t i = 0; i < cg.passes.size(); ++i)
        for (const auto& [pin, b] : cg.passes[i].bindings)
            EXPECT_LE(cg.resources[b.resource].writer, int(i));
}

TEST(Compile, RelativeSizesScalesAndRounding) {
    CompiledGraph cg = compile(R"json({
      "resources": {
        "quarter": {"format": "rgba8", "size": {"relative_to": "output", "scale": 0.25}},
        "aniso": {"format": "rgba8", "size": {"relative_to": "quarter", "scale": [0.5, 0.1]}},
        "chain": {"format": "rgba8", "size": {"relative_to": "aniso", "scale": 0.5}},
        "fixed": {"format": "rgba8", "size": [64, 32]},
        "tiny": {"format": "rgba8", "size": {"scale": 0.0001}},
        "tenth": {"format": "rgba8", "size": {"scale": 0.1}}
      },
      "passes": [
        {"name": "a", "type": "tonemap", "inputs": {"src": "h.ao"}, "outputs": {"dst": "quarter"}},
        {"name": "b", "type": "tonemap", "inputs": {"src": "h.ao"}, "outputs": {"dst": "aniso"}},
        {"name": "c", "type": "tonemap", "inputs": {"src": "h.ao"}, "outputs": {"dst": "chain"}},
        {"name": "d", "type": "tonemap", "inputs": {"src": "h.ao"}, "outputs": {"dst": "fixed"}},
        {"name": "e", "type": "tonemap", "inputs": {"src": "h.ao"}, "outputs": {"dst": "tiny"}},
        {"name": "f", "type": "tonemap", "inputs": {"src": "h.ao"}, "outputs": {"dst": "tenth"}},
        {"name": "h", "type": "ssao", "inputs": {"depth": "g.depth", "normal": "g.normal"}},
        {"name": "g", "type": "gbuffer"}
      ],
      "outputs": ["quarter", "aniso", "chain", "fixed", "tiny", "tenth"]})json",
                               {1001, 501});
    EXPECT_EQ(glm::ivec2(res(cg, "quarter").width, res(cg, "quarter").height), glm::ivec2(251, 126));  // ceil
    EXPECT_EQ(glm::ivec2(res(cg, "aniso").width, res(cg, "aniso").height), glm::ivec2(126, 13));
    EXPECT_EQ(glm::ivec2(res(cg, "chain").width, res(cg, "chain").height), glm::ivec2(63, 7));
    EXPECT_EQ(glm::ivec2(res(cg, "fixed").width, res(cg, "fixed").height), glm::ivec2(64, 32));
    EXPECT_EQ(glm::ivec2(res(cg, "tiny").width, res(cg, "tiny").height), glm::ivec2(1, 1));  // at least 1
    EXPECT_EQ(glm::ivec2(res(cg, "tenth").width, res(cg, "tenth").height), glm::ivec2(101, 51));
    EXPECT_EQ(glm::ivec2(res(cg, "h.ao").width, res(cg, "h.ao").height), glm::ivec2(501, 251));  // pin scale 0.5
    CompiledGraph exact = compile(R"json({"resources": {"t": {"format": "rgba8", "size": {"scale": 0.1}}},
        "passes": [{"name": "m", "type": "anyout", "outputs": {"dst": "t"}}], "outputs": ["t"]})json", {1000, 1000});
    EXPECT_EQ(res(exact, "t").width, 100);  // 0.1f is not exactly 0.1: no spurious round-up
}

TEST(Compile, FullMipChains) {
    CompiledGraph cg = compile(R"json({
      "resources": {"sq": {"format": "rgba8", "size": [1024, 1024], "mips": "full"},
                    "three": {"format": "rgba8", "size": [1024, 1024], "mips": 3}},
      "passes": [{"name": "m", "type": "mipgen", "inputs": {"src": "g.albedo"}},
                 {"name": "a", "type": "anyout", "outputs": {"dst": "sq"}},
                 {"name": "b", "type": "anyout", "outputs": {"dst": "three"}},
                 {"name": "g", "type": "gbuffer"}],
      "outputs": ["m.dst", "sq", "three"]})json");
    EXPECT_EQ(res(cg, "m.dst").mips, 11);  // 1920x1080: 1920 >> 10 = 1
    EXPECT_EQ(res(cg, "sq").mips, 11);
    EXPECT_EQ(res(cg, "three").mips, 3);
    EXPECT_EQ(res(cg, "three").bytes, size_t(4) * (1024 * 1024 + 512 * 512 + 256 * 256));
    EXPECT_EQ(res(cg, "g.albedo").mips, 1);
}

TEST(Compile, BufferSizes) {
    CompiledGraph cg = compile(R"json({
      "resources": {"small": {"kind": "buffer", "bytes_per_pixel": 4}, "fixed": {"kind": "buffer", "bytes": 4096}},
      "passes": [{"name": "p", "type": "particles"}, {"name": "c", "type": "counter"},
                 {"name": "p2", "type": "particles", "outputs": {"list": "small"}},
                 {"name": "c2", "type": "counter", "outputs": {"counts": "fixed"}},
                 {"name": "d", "type": "draw", "inputs": {"list": "p.list", "counts": "c.counts"}},
                 {"name": "d2", "type": "draw", "inputs": {"list": "small", "counts": "fixed"}}],
      "outputs": ["d.color", "d2.color"]})json",
                               {100, 50});
    EXPECT_EQ(res(cg, "p.list").kind, PinKind::Buffer);
    EXPECT_EQ(res(cg, "p.list").bytes, 16u * 100 * 50);
    EXPECT_EQ(res(cg, "c.counts").bytes, 1024u);
    EXPECT_EQ(res(cg, "small").bytes, 4u * 100 * 50);
    EXPECT_EQ(res(cg, "fixed").bytes, 4096u);
}

// A buffer whose size the writer's parameters decide (a volume's grid), with the
// graph's values, its variables and --set; no "bytes" needed in the graph.
TEST(Compile, BufferSizedByParameters) {
    const std::string text = R"json({
      "variables": {"g": {"type": "int", "default": 4, "min": 1, "max": 64}},
      "passes": [{"name": "v", "type": "volume"}, {"name": "w", "type": "volume", "params": {"grid": "$g"}},
                 {"name": "d", "type": "draw", "inputs": {"list": "v.cells", "counts": "w.cells"}}],
      "outputs": ["d.color"]})json";
    CompiledGraph cg = compile(text);
    EXPECT_EQ(res(cg, "v.cells").bytes, 8u * 8 * 8 * 4);
    EXPECT_EQ(res(cg, "w.cells").bytes, 4u * 4 * 4 * 4);
    GraphFile g = parse(text);
    std::vector<Diagnostic> diags;
    apply_overrides(g, {"v.grid=16", "g=2"}, fake_registry(), diags);
    ASSERT_TRUE(diags.empty());
    CompiledGraph set = compile_graph(g, fake_registry(), {64, 64});
    EXPECT_EQ(res(set, "v.cells").bytes, 16u * 16 * 16 * 4);
    EXPECT_EQ(res(set, "w.cells").bytes, 2u * 2 * 2 * 4);
}

TEST(Compile, HistoryResources) {
    CompiledGraph cg = compile(R"json({
      "resources": {"taa_out": {"format": "rgba16f", "history": true}},
      "passes": [
        {"name": "tonemap", "type": "tonemap", "inputs": {"src": "taa_out"}},
        {"name": "taa", "type": "taa", "inputs": {"current": "m.dst", "history": "taa_out@prev"},
         "outputs": {"resolved": "taa_out"}},
        {"name": "m", "type": "mix"}
      ],
      "outputs": ["tonemap.dst"]})json");
    EXPECT_EQ(order(cg), (std::vector<std::string>{"m", "taa", "tonemap"}));  // @prev does not order
    const CompiledResource& h = res(cg, "taa_out");
    EXPECT_TRUE(h.history);
    EXPECT_FALSE(h.transient());
    EXPECT_EQ(h.first_use, 0);  // alive the whole frame
    EXPECT_EQ(h.last_use, 2);
    EXPECT_TRUE(cg.passes[1].bindings.at("history").previous);
    EXPECT_FALSE(cg.passes[2].bindings.at("src").previous);
    EXPECT_EQ(cg.slots[h.slot].resources.size(), 1u);
    EXPECT_EQ(cg.slots[h.slot].bytes, 2 * h.bytes);  // two copies, swapped each frame
}

TEST(Compile, HistoryKeepsItsWriterAlive) {
    // "b" reads last frame's "acc"; "a" writes it and is needed for next frame even though
    // nothing reads "acc" this frame.
    CompiledGraph cg = compile(R"json({
      "resources": {"acc": {"format": "rgba16f", "history": true}},
      "passes": [{"name": "a", "type": "mix", "outputs": {"dst": "acc"}},
                 {"name": "b", "type": "mix", "inputs": {"a": "acc@prev"}}],
      "outputs": ["b.dst"]})json");
    EXPECT_EQ(order(cg), (std::vector<std::string>{"a", "b"}));
    EXPECT_TRUE(cg.culled.empty());
}

TEST(Compile, LifetimesOverTheOrder) {
    CompiledGraph cg = compile(R"json({"passes": [
        {"name": "a", "type": "mix"}, {"name": "b", "type": "mix", "inputs": {"a": "a.dst"}},
        {"name": "c", "type": "mix", "inputs": {"a": "b.dst"}}, {"name": "d", "type": "mix", "inputs": {"a": "a.dst", "b": "c.dst"}},
        {"name": "e", "type": "mix", "inputs": {"a": "d.dst"}}],
      "outputs": ["e.dst", "b.dst"]})json");
    EXPECT_EQ(std::make_pair(res(cg, "a.dst").first_use, res(cg, "a.dst").last_use), std::make_pair(0, 3));
    EXPECT_EQ(std::make_pair(res(cg, "c.dst").first_use, res(cg, "c.dst").last_use), std::make_pair(2, 3));
    // Captured/presented outputs live to the end.
    EXPECT_EQ(std::make_pair(res(cg, "b.dst").first_use, res(cg, "b.dst").last_use), std::make_pair(1, 4));
    EXPECT_TRUE(res(cg, "b.dst").captured);
    EXPECT_EQ(cg.outputs[1].resource, "b.dst");
}

TEST(Compile, OutputSizeMustBePositive) {
    EXPECT_THROW(compile(kDeferred, {0, 100}), GraphError);
}
