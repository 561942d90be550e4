// Parameter declarations: one declaration drives validation, --set text and the docs.
#include <pathlet/pass.hpp>
#include <pathlet/shader.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace pathlet;

namespace {
struct Nop : Pass {
    void execute(PassContext&) override {}
};
PassTypeInfo sample_type() {
    return PassTypeBuilder("sample", "a pass for tests")
        .param_int("samples", 32, 1, 128, "samples")
        .param_float("strength", 1.0, 0.0, 5.0, "strength")
        .param_enum("growth", "linear", {"linear", "running_sum"}, "radius growth")
        .param_color("halo_color", {0, 0, 0}, "halo colour")
        .param_bool("pyramid", true, "use the pyramid")
        .input_texture("normal_depth", "rgba16f", "G-buffer")
        .input_texture("extra", "any", "optional", {.optional = true})
        .output_texture("ao", "r16f", "ambient occlusion")
        .make<Nop>();
}
std::string coerce(const PassTypeInfo& t, const std::string& p, const json& v, json* out = nullptr) {
    json tmp;
    return t.param(p)->coerce(v, out ? *out : tmp);
}
}  // namespace

TEST(ParamDecl, AcceptsValidValuesAndConvertsThem) {
    auto t = sample_type();
    json out;
    EXPECT_EQ(coerce(t, "samples", 58, &out), "");
    EXPECT_EQ(out.get<int>(), 58);
    EXPECT_EQ(coerce(t, "strength", 2, &out), "");  // an int is a fine float
    EXPECT_DOUBLE_EQ(out.get<double>(), 2.0);
    EXPECT_EQ(coerce(t, "halo_color", "#ff8000", &out), "");
    EXPECT_NEAR(out[1].get<double>(), 128.0 / 255.0, 1e-9);
    EXPECT_EQ(coerce(t, "growth", "running_sum", &out), "");
}

TEST(ParamDecl, RejectsWrongTypesAndRangesWithAReason) {
    auto t = sample_type();
    EXPECT_NE(coerce(t, "samples", 0).find("out of range [1, 128]"), std::string::npos);
    EXPECT_NE(coerce(t, "samples", 2.5).find("integer"), std::string::npos);
    EXPECT_NE(coerce(t, "strength", "high").find("number"), std::string::npos);
    EXPECT_NE(coerce(t, "growth", "cubic").find("linear, running_sum"), std::string::npos);
    EXPECT_NE(coerce(t, "halo_color", json::array({1, 2})).find("3 numbers"), std::string::npos);
    EXPECT_NE(coerce(t, "halo_color", json::array({1, 2, 0})).find("0..1"), std::string::npos);
    EXPECT_NE(coerce(t, "pyramid", 1).find("bool"), std::string::npos);
}

TEST(ParamDecl, CommandLineTextIsParsedByTheDeclaredType) {
    auto t = sample_type();
    json out;
    EXPECT_EQ(t.param("samples")->coerce_text("58", out), "");
    EXPECT_EQ(out.get<int>(), 58);
    EXPECT_EQ(t.param("pyramid")->coerce_text("false", out), "");
    EXPECT_FALSE(out.get<bool>());
    EXPECT_EQ(t.param("growth")->coerce_text("linear", out), "");
    EXPECT_EQ(t.param("halo_color")->coerce_text("1,0.5,0", out), "");
    EXPECT_EQ(t.param("halo_color")->coerce_text("#00ff00", out), "");
    EXPECT_NE(t.param("strength")->coerce_text("lots", out), "");
}

TEST(PassTypeInfo, DescribeListsEveryParameterAndPin) {
    std::string d = sample_type().describe();
    for (const char* word : {"samples", "strength", "growth", "halo_color", "pyramid", "normal_depth", "rgba16f",
                             "optional", "ao", "r16f", "range [1, 128]", "linear, running_sum"})
        EXPECT_NE(d.find(word), std::string::npos) << word << "\n" << d;
}

TEST(Params, UndeclaredNameIsAProgrammingErrorNamingThePass) {
    Params p("myao", sample_type().default_params());
    EXPECT_EQ(p.i("samples"), 32);
    EXPECT_TRUE(p.b("pyramid"));
    try {
        p.f("radius");
        FAIL();
    } catch (const std::logic_error& e) {
        EXPECT_NE(std::string(e.what()).find("myao"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("radius"), std::string::npos);
    }
}

// pathlet::whole_exponent: which exponents a pass compiles in as products (shaders/pow_whole.glsl).
TEST(Shader, WholeExponentDefinesOnlyWholeNumbersInRange) {
    EXPECT_EQ(pathlet::whole_exponent("E", 50.0f), std::vector<std::string>{"E 50"});
    EXPECT_EQ(pathlet::whole_exponent("E", 1.0f), std::vector<std::string>{"E 1"});
    EXPECT_EQ(pathlet::whole_exponent("E", 2047.0f), std::vector<std::string>{"E 2047"});
    EXPECT_TRUE(pathlet::whole_exponent("E", 50.5f).empty());
    EXPECT_TRUE(pathlet::whole_exponent("E", 0.5f).empty());
    EXPECT_TRUE(pathlet::whole_exponent("E", 0.0f).empty());
    EXPECT_TRUE(pathlet::whole_exponent("E", 2048.0f).empty());  // pow_whole's loop covers 11 bits
    EXPECT_TRUE(pathlet::whole_exponent("E", std::nanf("")).empty());
}
