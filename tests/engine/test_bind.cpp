// Binding by declaration (pass.hpp): declared parameters reach u_<name>, texture pins and
// internal textures their samplers u_<pin>, without a line of C++ in the pass; a uniform of the
// wrong type is refused by name; the executor hands every pass the documented GL state.
#include "engine_test_util.hpp"

#include "graph/graph_model.hpp"

#include <pathlet/pass.hpp>

using namespace pathlet;
using namespace pathlet::testing_util;

namespace {

struct Nop : Pass {
    void execute(PassContext&) override {}
};

void load_fixtures() {
    try {
        runtime().host.load_file(std::string(PATHLET_FIXTURE_DIR) + "/pathlet_bind_probe.so");
    } catch (const PluginError&) {
        // already loaded by an earlier test
    }
}

// The probe's first row, as floats: pixel x at [4x .. 4x+3].
std::vector<float> probe(std::vector<std::string> sets = {}, int ssaa = 1) {
    load_fixtures();
    Scene scene = tiny_scene();
    RenderOptions o;
    o.graph_path = test_file("graphs/bind_probe.json");
    o.size = {4, 1};
    o.ssaa = ssaa;
    o.sets = std::move(sets);
    o.warmup = 0;
    o.write_images = false;
    o.quiet = true;
    std::vector<float> row;
    render(runtime(), scene, o, [&](const Executor& e, size_t) {
        Texture t = e.texture("probe");
        std::vector<float> all(size_t(t.width) * t.height * 4);
        glGetTextureImage(t.id, 0, GL_RGBA, GL_FLOAT, GLsizei(all.size() * 4), all.data());
        row.assign(all.begin(), all.begin() + 16);
    });
    return row;
}

}  // namespace

TEST(Bind, DeclaredParametersReachTheirUniforms) {
    std::vector<float> v = probe();
    ASSERT_EQ(v.size(), 16u);
    EXPECT_EQ(v[0], 3.0f);   // count
    EXPECT_EQ(v[1], 0.5f);   // gain
    EXPECT_EQ(v[2], 1.0f);   // flag
    EXPECT_EQ(v[3], 1.0f);   // mode "b": index 1
    EXPECT_EQ(v[4], 0.25f);  // tint
    EXPECT_EQ(v[5], 0.5f);
    EXPECT_EQ(v[6], 1.0f);
    EXPECT_EQ(v[7], 1.5f);   // radius_px at pixel scale 1
}

TEST(Bind, SetValuesArriveAndEnumsAsTheirIndex) {
    std::vector<float> v = probe({"probe.count=7", "probe.gain=2.25", "probe.flag=false", "probe.mode=c",
                                  "probe.tint=#ff0000"});
    EXPECT_EQ(v[0], 7.0f);
    EXPECT_EQ(v[1], 2.25f);
    EXPECT_EQ(v[2], 0.0f);
    EXPECT_EQ(v[3], 2.0f);
    EXPECT_EQ(v[4], 1.0f);
    EXPECT_EQ(v[5], 0.0f);
}

TEST(Bind, PixelParametersScaleWithSupersampling) {
    std::vector<float> v = probe({}, 3);  // rendered 3x3 larger: pixels then mean 3 render pixels
    EXPECT_EQ(v[7], 4.5f);                // radius_px x 3
    EXPECT_EQ(v[0], 3.0f);                // count is not a length: unscaled
}

TEST(Bind, PinsAndInternalTexturesReachTheirSamplers) {
    std::vector<float> v = probe();
    EXPECT_NEAR(v[8], 0.2f, 1.0f / 255);  // src: the clear's colour (rgba8)
    EXPECT_NEAR(v[9], 0.4f, 1.0f / 255);
    EXPECT_NEAR(v[10], 0.6f, 1.0f / 255);
    EXPECT_NEAR(v[11], 0.8f, 1.0f / 255);
    EXPECT_EQ(v[12], 0.25f);  // scratch, the pass's internal texture
    EXPECT_EQ(v[15], 1.0f);
}

TEST(Bind, AUniformOfTheWrongTypeIsAnErrorNamingBoth) {
    try {
        probe({"probe.shader=bind_probe_mistyped.frag"});
        FAIL() << "a vec2 u_gain for a float parameter must not bind";
    } catch (const std::exception& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("pass 'probe'"), std::string::npos) << msg;
        EXPECT_NE(msg.find("'u_gain' is vec2"), std::string::npos) << msg;
        EXPECT_NE(msg.find("parameter 'gain' is float"), std::string::npos) << msg;
    }
}

TEST(Bind, SamplerByNameOfATypoThrows) {
    load_fixtures();
    ShaderProgram p = ShaderProgram::from_files({"fullscreen.vert", "bind_probe.frag"},
                                                {test_file("shaders"), source("shaders")});
    EXPECT_NO_THROW(p.bind_texture("u_src", 0));
    EXPECT_THROW(p.bind_texture("u_scr", 0), ShaderError);
    EXPECT_THROW(p.bind_texture("u_gain", 0), ShaderError);  // not a sampler
}

TEST(Bind, EveryPassStartsFromTheDocumentedGlState) {
    load_fixtures();
    const Image clean = render_resource(test_file("graphs/leaky.json"), "blurred", {24, 16}, {"leak=false"});
    const Image after_leak = render_resource(test_file("graphs/leaky.json"), "blurred", {24, 16});
    ASSERT_EQ(clean.pixels.size(), after_leak.pixels.size());
    EXPECT_EQ(clean.pixels, after_leak.pixels);
    float sum = 0;  // and the picture is there at all (a masked or scissored draw leaves zeros)
    for (float x : clean.pixels) sum += x;
    EXPECT_GT(sum, 0.1f * float(clean.pixels.size()));
}

TEST(Bind, InternalTexturesAreNotBoundByGraphsNorReadByOtherPasses) {
    load_fixtures();
    const std::string bound = R"({"version": 1, "passes": [
        {"name": "probe", "type": "bind_probe", "outputs": {"color": "c", "scratch": "s"}}],
        "resources": {"c": {}, "s": {}}, "outputs": [{"resource": "c"}]})";
    auto diags = validate_graph(parse_graph_json(bound, "bound.json"), runtime().registry);
    ASSERT_FALSE(diags.empty());
    EXPECT_NE(diags[0].str().find("bound.json:/passes/0/outputs/scratch: 'scratch' is bind_probe's internal texture"),
              std::string::npos)
        << diags[0].str();
    const std::string read = R"({"version": 1, "passes": [
        {"name": "probe", "type": "bind_probe", "outputs": {"color": "c"}},
        {"name": "blur", "type": "blur", "inputs": {"src": "probe.scratch"}, "outputs": {"dst": "d"}}],
        "resources": {"c": {}, "d": {}}, "outputs": [{"resource": "d"}]})";
    diags = validate_graph(parse_graph_json(read, "read.json"), runtime().registry);
    ASSERT_FALSE(diags.empty());
    EXPECT_NE(diags[0].str().find("'probe.scratch' is a pass's internal texture"), std::string::npos) << diags[0].str();
    // A graph output may still capture one, to look at it.
    const std::string captured = R"({"version": 1, "passes": [
        {"name": "probe", "type": "bind_probe", "outputs": {"color": "c"}}],
        "resources": {"c": {}}, "outputs": [{"resource": "c"}, {"resource": "probe.scratch"}]})";
    EXPECT_TRUE(validate_graph(parse_graph_json(captured, "captured.json"), runtime().registry).empty());
}

TEST(Params, EnumIndexAndTypedGetter) {
    PassTypeInfo t = PassTypeBuilder("t", "t").param_enum("mode", "box", {"gaussian", "box"}, "m").make<Nop>();
    Params p("pass", t.default_params(), &t);
    enum class Mode { gaussian, box };
    EXPECT_EQ(p.index("mode"), 1);
    EXPECT_EQ(p.e<Mode>("mode"), Mode::box);
    Params untyped("pass", t.default_params());
    EXPECT_THROW(untyped.index("mode"), std::logic_error);
}
