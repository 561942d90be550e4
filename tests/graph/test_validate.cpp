// One test per validation rule: each asserts the JSON pointer and a key phrase of the message.
#include "fake_registry.hpp"

using namespace pathlet;
using namespace pathlet::test;

namespace {

std::string with(std::string text, const std::string& from, const std::string& to) {
    size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

// A valid deferred graph; tests splice one fault into it.
std::string deferred(const std::string& ssao_extra = "", const std::string& resources_extra = "",
                     const std::string& passes_extra = "", const std::string& outputs = R"(["ldr"])") {
    return R"json({
      "name": "deferred",
      "variables": {
        "ao_radius": {"type": "float", "default": 1.0, "min": 0, "max": 8},
        "use_ssao": {"type": "bool", "default": true},
        "quality": {"type": "enum", "default": "sphere", "choices": ["hemisphere", "sphere", "cube"]}
      },
      "resources": {
        "hdr": {"format": "rgba16f"},
        "ldr": {"format": "rgba8"})json" +
           resources_extra + R"json(
      },
      "passes": [
        {"name": "gbuffer", "type": "gbuffer"},
        {"name": "ssao", "type": "ssao", "enabled": "$use_ssao",
         "inputs": {"depth": "gbuffer.depth", "normal": "gbuffer.normal"})json" +
           ssao_extra + R"json(},
        {"name": "lighting", "type": "lighting",
         "inputs": {"depth": "gbuffer.depth", "normal": "gbuffer.normal", "albedo": "gbuffer.albedo", "ao": "ssao.ao"},
         "outputs": {"color": "hdr"}},
        {"name": "tonemap", "type": "tonemap", "inputs": {"src": "hdr"}, "outputs": {"dst": "ldr"}})json" +
           passes_extra + R"json(
      ],
      "outputs": )json" + outputs + "}";
}

}  // namespace

TEST(Validate, TheBaseGraphIsValid) {
    auto d = problems(deferred());
    EXPECT_TRUE(d.empty()) << all(d);
}

TEST(Validate, UnknownPassTypeSuggestsARegisteredOne) {
    auto d = problems(deferred("", "", R"(, {"name": "x", "type": "ssoa", "inputs": {"depth": "gbuffer.depth"}})"));
    EXPECT_TRUE(has_problem(d, "/passes/4/type", "unknown pass type 'ssoa' (did you mean 'ssao'?)"));
    EXPECT_EQ(d.size(), 1u) << all(d);  // its params and pins are not checked against nothing
}

TEST(Validate, UnknownParameterSuggestsTheClosest) {
    auto d = problems(deferred(R"(, "params": {"raduis": 1})"));
    EXPECT_TRUE(has_problem(d, "/passes/1/params/raduis", "unknown parameter 'raduis' for pass type 'ssao' (did you mean 'radius'?)"));
}

TEST(Validate, WrongParameterType) {
    auto d = problems(deferred(R"(, "params": {"radius": "big"})"));
    EXPECT_TRUE(has_problem(d, "/passes/1/params/radius", "expects a number"));
}

TEST(Validate, ParameterOutOfRange) {
    auto d = problems(deferred(R"(, "params": {"samples": 100})"));
    EXPECT_TRUE(has_problem(d, "/passes/1/params/samples", "out of range"));
}

TEST(Validate, BadEnumValue) {
    auto d = problems(deferred(R"(, "params": {"mode": "spher"})"));
    EXPECT_TRUE(has_problem(d, "/passes/1/params/mode", "is not one of hemisphere, sphere"));
}

TEST(Validate, UnknownVariableSuggestsTheClosest) {
    auto d = problems(deferred(R"(, "params": {"radius": "$ao_radus"})"));
    EXPECT_TRUE(has_problem(d, "/passes/1/params/radius", "unknown variable '$ao_radus' (did you mean '$ao_radius'?)"));
}

TEST(Validate, VariableOfIncompatibleType) {
    auto d = problems(deferred(R"(, "params": {"samples": "$use_ssao"})"));
    EXPECT_TRUE(has_problem(d, "/passes/1/params/samples", "variable '$use_ssao' is bool but parameter 'samples' is int"));
}

TEST(Validate, VariableValueOutsideTheParameterRange) {
    auto d = problems(deferred(R"(, "params": {"radius": "$ao_radius"})", "", "", R"(["ldr"])"));
    EXPECT_TRUE(d.empty()) << all(d);  // 1.0 fits radius [0, 4]
    std::string text = deferred(R"(, "params": {"radius": "$ao_radius"})");
    text = with(text, "\"default\": 1.0", "\"default\": 6.0");
    d = problems(text);
    EXPECT_TRUE(has_problem(d, "/passes/1/params/radius", "(from $ao_radius = 6.0) value 6.0 is out of range"));
}

TEST(Validate, EnumVariableIsCheckedAgainstTheParameterChoices) {
    auto d = problems(deferred(R"(, "params": {"mode": "$quality"})"));
    EXPECT_TRUE(d.empty()) << all(d);
    std::string text = deferred(R"(, "params": {"mode": "$quality"})");
    text = with(text, "\"default\": \"sphere\"", "\"default\": \"cube\"");
    d = problems(text);
    EXPECT_TRUE(has_problem(d, "/passes/1/params/mode", "'cube' is not one of"));
}

TEST(Validate, EnabledNeedsABoolVariable) {
    std::string text = deferred();
    text = with(text, "\"$use_ssao\"", "\"$ao_radius\"");
    EXPECT_TRUE(has_problem(problems(text), "/passes/1/enabled", "enabled needs a bool variable, but '$ao_radius' is float"));
    text = deferred();
    text = with(text, "\"$use_ssao\"", "\"$use_sao\"");
    EXPECT_TRUE(has_problem(problems(text), "/passes/1/enabled", "did you mean '$use_ssao'?"));
}

TEST(Validate, UnknownPinSuggestsTheClosest) {
    std::string text = deferred();
    text = with(text, "{\"depth\": \"gbuffer.depth\", \"normal\"", "{\"dpeth\": \"gbuffer.depth\", \"normal\"");
    auto d = problems(text);
    EXPECT_TRUE(has_problem(d, "/passes/1/inputs/dpeth", "has no input pin 'dpeth' (did you mean 'depth'?)"));
    EXPECT_TRUE(has_problem(d, "/passes/1/inputs", "required input 'depth' of pass type 'ssao' is not connected"));
}

TEST(Validate, OutputPinBoundAsInput) {
    auto d = problems(deferred("", "", R"(, {"name": "t2", "type": "tonemap", "inputs": {"src": "hdr", "dst": "ldr"}})"));
    EXPECT_TRUE(has_problem(d, "/passes/4/inputs/dst", "'dst' is an output: bind it under \"outputs\""));
}

TEST(Validate, UnconnectedRequiredInput) {
    std::string text = deferred();
    text = with(text, ", \"normal\": \"gbuffer.normal\"}", "}");
    auto d = problems(text);
    EXPECT_TRUE(has_problem(d, "/passes/1/inputs", "required input 'normal' of pass type 'ssao' is not connected"));
    EXPECT_EQ(d.size(), 1u) << all(d);  // "ao" and "lights" of lighting are optional
}

TEST(Validate, UnknownResourceSuggestsTheClosest) {
    auto d = problems(deferred("", "", R"(, {"name": "t2", "type": "tonemap", "inputs": {"src": "hrd"}})"));
    EXPECT_TRUE(has_problem(d, "/passes/4/inputs/src", "unknown resource 'hrd' (did you mean 'hdr'?)"));
}

TEST(Validate, UnknownPassPinReference) {
    auto d = problems(deferred("", "",
                               R"(, {"name": "t2", "type": "tonemap", "inputs": {"src": "gbufer.normal"}},
                                  {"name": "t3", "type": "tonemap", "inputs": {"src": "gbuffer.normals"}})"));
    EXPECT_TRUE(has_problem(d, "/passes/4/inputs/src", "names no resource and no pass 'gbufer' (did you mean 'gbuffer'?)"));
    EXPECT_TRUE(has_problem(d, "/passes/5/inputs/src", "has no output pin 'normals' (did you mean 'normal'?)"));
}

TEST(Validate, OutputBoundToAnUndeclaredResource) {
    auto d = problems(deferred("", "", R"(, {"name": "t2", "type": "tonemap", "inputs": {"src": "hdr"}, "outputs": {"dst": "ldr2"}})"));
    EXPECT_TRUE(has_problem(d, "/passes/4/outputs/dst", "unknown resource 'ldr2'"));
    EXPECT_TRUE(has_problem(d, "/passes/4/outputs/dst", "leave the pin unbound to get 't2.dst'"));
}

TEST(Validate, KindMismatchTextureVersusBuffer) {
    std::string text = deferred("", R"(, "list": {"kind": "buffer", "bytes": 64})",
                                R"(, {"name": "l2", "type": "lighting", "inputs": {"depth": "gbuffer.depth",
                                      "normal": "gbuffer.normal", "albedo": "gbuffer.albedo", "lights": "hdr"}},
                                   {"name": "p", "type": "particles", "outputs": {"list": "ldr"}},
                                   {"name": "t2", "type": "tonemap", "inputs": {"src": "list"}})");
    auto d = problems(text);
    EXPECT_TRUE(has_problem(d, "/passes/4/inputs/lights", "pin 'lights' takes a buffer but 'hdr' is a texture"));
    EXPECT_TRUE(has_problem(d, "/passes/5/outputs/list", "pin 'list' writes a buffer but 'ldr' is a texture"));
    EXPECT_TRUE(has_problem(d, "/passes/6/inputs/src", "pin 'src' takes a texture but 'list' is a buffer"));
}

TEST(Validate, FormatMismatch) {
    std::string text = deferred();
    text = with(text, "\"albedo\": \"gbuffer.albedo\"", "\"albedo\": \"gbuffer.normal\"");
    text = with(text, "\"hdr\": {\"format\": \"rgba16f\"}", "\"hdr\": {\"format\": \"rgba32f\"}");
    auto d = problems(text);
    EXPECT_TRUE(has_problem(d, "/passes/2/inputs/albedo", "format mismatch: pin 'albedo' of 'lighting' takes rgba8 but 'gbuffer.normal' is rgba16f"));
    EXPECT_TRUE(has_problem(d, "/passes/2/outputs/color", "format mismatch: pin 'color' of 'lighting' writes rgba16f but resource 'hdr' is rgba32f"));
}

TEST(Validate, PrevOfANonHistoryResource) {
    auto d = problems(deferred("", R"(, "taa_out": {"format": "rgba16f"})",
                               R"(, {"name": "taa", "type": "taa", "inputs": {"current": "hdr", "history": "hdr@prev"},
                                     "outputs": {"resolved": "taa_out"}})"));
    EXPECT_TRUE(has_problem(d, "/passes/4/inputs/history", "'hdr@prev' reads last frame's 'hdr', but it is not a history resource"));
}

TEST(Validate, TwoWritersOfOneResource) {
    auto d = problems(deferred("", "", R"(, {"name": "t2", "type": "tonemap", "inputs": {"src": "hdr"}, "outputs": {"dst": "ldr"}})"));
    EXPECT_TRUE(has_problem(d, "/passes/4/outputs/dst", "resource 'ldr' is already written by pass 'tonemap' (at /passes/3/outputs/dst)"));
    EXPECT_TRUE(has_problem(d, "/passes/4/outputs/dst", "one writer per resource"));
}

TEST(Validate, ReadModifyWriteOfOneResource) {
    auto d = problems(deferred("", R"(, "acc": {"format": "rgba16f"})",
                               R"(, {"name": "acc", "type": "blur", "inputs": {"src": "acc"}, "outputs": {"dst": "acc"}})"));
    EXPECT_TRUE(has_problem(d, "/passes/4/inputs/src", "pass 'acc' reads and writes 'acc'"));
    EXPECT_TRUE(has_problem(d, "/passes/4/inputs/src", "read 'acc@prev'"));
}

TEST(Validate, DuplicatePassNames) {
    auto d = problems(deferred("", "", R"(, {"name": "ssao", "type": "blur", "inputs": {"src": "hdr"}})"));
    EXPECT_TRUE(has_problem(d, "/passes/4/name", "duplicate pass name 'ssao' (first at /passes/1)"));
}

TEST(Validate, CyclesNameThePassesInTheCycle) {
    auto d = problems(R"json({
      "passes": [
        {"name": "a", "type": "mix", "inputs": {"a": "c.dst"}},
        {"name": "b", "type": "mix", "inputs": {"a": "a.dst"}},
        {"name": "c", "type": "mix", "inputs": {"a": "b.dst"}},
        {"name": "d", "type": "mix", "inputs": {"a": "e.dst"}},
        {"name": "e", "type": "mix", "inputs": {"a": "d.dst"}},
        {"name": "f", "type": "mix", "inputs": {"a": "a.dst", "b": "d.dst"}}
      ],
      "outputs": ["f.dst"]
    })json");
    EXPECT_TRUE(has_problem(d, "/passes/0", "passes form a cycle: a -> b -> c -> a"));
    EXPECT_TRUE(has_problem(d, "/passes/3", "passes form a cycle: d -> e -> d"));
    EXPECT_EQ(d.size(), 2u) << all(d);
}

TEST(Validate, SizeRelativeToAnUnknownResource) {
    auto d = problems(deferred("", R"(, "half": {"format": "rgba16f", "size": {"relative_to": "hdrr", "scale": 0.5}})",
                               R"(, {"name": "b", "type": "blur", "inputs": {"src": "hdr"}, "outputs": {"dst": "half"}})"));
    EXPECT_TRUE(has_problem(d, "/resources/half/size", "relative to unknown resource 'hdrr' (did you mean 'hdr'?)"));
}

TEST(Validate, CyclicRelativeSizesAreReportedOnce) {
    auto d = problems(deferred("", R"(,
        "a": {"format": "rgba16f", "size": {"relative_to": "b"}},
        "b": {"format": "rgba16f", "size": {"relative_to": "a"}},
        "c": {"format": "rgba16f", "size": {"relative_to": "a"}})"));
    EXPECT_TRUE(has_problem(d, "/resources/a/size", "size of 'a' is relative to itself: a -> b -> a"));
    EXPECT_EQ(d.size(), 1u) << all(d);
}

TEST(Validate, SizeRelativeToABuffer) {
    auto d = problems(deferred("", R"(, "list": {"kind": "buffer", "bytes": 64},
                                       "half": {"format": "rgba16f", "size": {"relative_to": "list"}})"));
    EXPECT_TRUE(has_problem(d, "/resources/half/size", "which is a buffer"));
}

TEST(Validate, OutputsNamingUnknownResources) {
    auto d = problems(deferred("", "", "", R"(["ldr", {"resource": "lddr"}, "tonemap.dts", "ldr@prev"])"));
    EXPECT_TRUE(has_problem(d, "/outputs/1/resource", "unknown resource 'lddr' (did you mean 'ldr'?)"));
    EXPECT_TRUE(has_problem(d, "/outputs/2/resource", "has no output pin 'dts' (did you mean 'dst'?)"));
    EXPECT_TRUE(has_problem(d, "/outputs/3/resource", "cannot be last frame's content"));
}

TEST(Validate, EmptyOutputsList) {
    auto d = problems(deferred("", "", "", "[]"));
    EXPECT_TRUE(has_problem(d, "/outputs", "the graph has no outputs"));
}

TEST(Validate, ResourceReadButNeverWritten) {
    auto d = problems(deferred("", R"(, "lut": {"format": "rgba8"}, "white": {"format": "r8", "persistent": true})",
                               R"(, {"name": "t2", "type": "tonemap", "inputs": {"src": "lut"}},
                                  {"name": "t3", "type": "tonemap", "inputs": {"src": "white"}})"));
    EXPECT_TRUE(has_problem(d, "/passes/4/inputs/src", "'lut' is read but no pass writes it"));
    EXPECT_EQ(d.size(), 1u) << all(d);  // a persistent resource may be filled outside the graph
}

TEST(Validate, FormatLeftOpenByPinAndResource) {
    auto d = problems(R"json({"resources": {"x": {"size": [4, 4]}, "y": {"format": "r32f"}},
      "passes": [{"name": "a", "type": "anyout", "outputs": {"dst": "x"}},
                 {"name": "b", "type": "anyout"},
                 {"name": "c", "type": "anyout", "outputs": {"dst": "y"}}],
      "outputs": ["x", "b.dst", "y"]})json");
    EXPECT_TRUE(has_problem(d, "/resources/x", "format of 'x' is unknown"));
    EXPECT_TRUE(has_problem(d, "/passes/1", "format of 'b.dst' is unknown"));
    EXPECT_EQ(d.size(), 2u) << all(d);
}

TEST(Validate, EveryErrorIsReportedAtOnce) {
    const std::string text = deferred(R"(, "params": {"raduis": 1, "samples": 0})", "",
                                      R"(, {"name": "x", "type": "blurr", "inputs": {"src": "hdr"}},
                                         {"name": "t2", "type": "tonemap", "inputs": {"src": "hdr"}, "outputs": {"dst": "ldr"}})",
                                      R"(["ldr", "nothing"])");
    auto d = problems(text);
    EXPECT_TRUE(has_problem(d, "/passes/1/params/raduis", "did you mean 'radius'?"));
    EXPECT_TRUE(has_problem(d, "/passes/1/params/samples", "out of range"));
    EXPECT_TRUE(has_problem(d, "/passes/4/type", "did you mean 'blur'?"));
    EXPECT_TRUE(has_problem(d, "/passes/5/outputs/dst", "already written"));
    EXPECT_TRUE(has_problem(d, "/outputs/1/resource", "unknown resource 'nothing'"));
    EXPECT_EQ(d.size(), 5u) << all(d);
    try {
        compile(text);
        FAIL() << "compiled";
    } catch (const GraphError& e) {
        EXPECT_EQ(e.diagnostics.size(), 5u);
        const std::string what = e.what();
        EXPECT_NE(what.find("test.json:/passes/1/params/raduis: "), std::string::npos) << what;
        EXPECT_NE(what.find("test.json:/outputs/1/resource: "), std::string::npos) << what;
    }
}

// Values that must agree are checked when the graph compiles, each error naming both sides.
namespace {
std::string agreeing(const std::string& former_params, const std::string& reader_params, bool through_blur) {
    const std::string src = through_blur ? "blur.dst" : "former.dst";
    return R"({"name": "agree", "passes": [
        {"name": "former", "type": "former", "params": )" + former_params + R"(},
        {"name": "blur", "type": "blur", "inputs": {"src": "former.dst"}},
        {"name": "reader", "type": "reader", "params": )" + reader_params + R"(, "inputs": {"src": ")" + src + R"("}},
        {"name": "range", "type": "ranged", "params": {"lo": 3, "hi": 5}}],
      "outputs": ["reader.dst", "range.dst"]})";
}
}  // namespace

TEST(Validate, AParameterAboveTheOtherEndOfItsRangeNamesBoth) {
    auto d = problems(with(agreeing("{}", "{}", false), R"("lo": 3, "hi": 5)", R"("lo": 8, "hi": 5)"));
    EXPECT_TRUE(has_problem(d, "/passes/3/params/lo", "pass 'range': lo = 8 is above hi = 5; lo must not exceed hi"));
    EXPECT_EQ(d.size(), 1u) << all(d);
    // The default of the other end counts; an automatic value (<= 0 here) is not compared.
    d = problems(with(agreeing("{}", "{}", false), R"("lo": 3, "hi": 5)", R"("lo": 3)"));
    EXPECT_TRUE(has_problem(d, "/passes/3/params/lo", "lo = 3 is above hi = 2")) << "hi's default is 2";
    for (const char* fine : {R"("lo": 0, "hi": 5)", R"("lo": 8, "hi": -1)", R"("lo": 5, "hi": 5)"}) {
        d = problems(with(agreeing("{}", "{}", false), R"("lo": 3, "hi": 5)", fine));
        EXPECT_TRUE(d.empty()) << fine << "\n" << all(d);
    }
}

TEST(Validate, APassThatMustAgreeWithWhatWroteItsInputNamesBothPasses) {
    for (bool through : {false, true}) {
        auto d = problems(agreeing(R"({"form": "b"})", R"({"form": "a", "gain": 3})", through));
        EXPECT_TRUE(has_problem(d, "/passes/2/params/form",
                                "pass 'reader' (reader) has form = a but pass 'former' (former), which its input 'src' "
                                "comes from, has form = b"))
            << (through ? "through blur" : "directly");
        EXPECT_EQ(d.size(), 1u) << all(d);  // gain is the reader's own; width agrees (both default)
        d = problems(agreeing(R"({"width": 2})", "{}", through));
        EXPECT_TRUE(has_problem(d, "/passes/2", "has width = 1 but pass 'former' (former)")) << "a default counts too";
        d = problems(agreeing(R"({"form": "b", "width": 3})", R"({"form": "b", "width": 3})", through));
        EXPECT_TRUE(d.empty()) << all(d);
    }
}
