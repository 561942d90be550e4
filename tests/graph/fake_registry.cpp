#include "fake_registry.hpp"

#include <cmath>

namespace pathlet::test {

namespace {

struct NoopPass : Pass {
    void execute(PassContext&) override {}
};

PassRegistry make() {
    PassRegistry reg;
    auto add = [&](PassTypeBuilder b) { reg.add(b.make<NoopPass>()); };
    add(PassTypeBuilder("gbuffer", "G-buffer")
            .param_bool("cull_backfaces", true, "cull")
            .output_texture("depth", "depth32f", "depth")
            .output_texture("normal", "rgba16f", "normals")
            .output_texture("albedo", "rgba8", "albedo"));
    add(PassTypeBuilder("ssao", "ambient occlusion")
            .param_float("radius", 0.5, 0.0, 4.0, "radius")
            .param_int("samples", 16, 1, 64, "samples")
            .param_enum("mode", "hemisphere", {"hemisphere", "sphere"}, "kernel")
            .param_color("tint", {1, 1, 1}, "tint")
            .input_texture("depth", "depth32f", "depth")
            .input_texture("normal", "any", "normals")
            .output_texture("ao", "r8", "occlusion", {.scale = 0.5f}));
    add(PassTypeBuilder("blur", "blur")
            .param_int("taps", 5, 1, 31, "taps")
            .input_texture("src", "any", "source")
            .output_texture("dst", "rgba16f", "blurred"));
    add(PassTypeBuilder("lighting", "deferred lighting")
            .input_texture("depth", "depth32f", "depth")
            .input_texture("normal", "rgba16f", "normals")
            .input_texture("albedo", "rgba8", "albedo")
            .input_texture("ao", "r8", "occlusion", {.optional = true})
            .input_buffer("lights", "lights", {.optional = true})
            .output_texture("color", "rgba16f", "lit"));
    add(PassTypeBuilder("taa", "temporal AA")
            .input_texture("current", "rgba16f", "this frame")
            .input_texture("history", "rgba16f", "last frame")
            .output_texture("resolved", "rgba16f", "resolved"));
    add(PassTypeBuilder("tonemap", "tonemap")
            .param_float("exposure", 0.0, -10.0, 10.0, "EV")
            .param_enum("operator", "aces", {"aces", "reinhard"}, "curve")
            .input_texture("src", "any", "hdr")
            .output_texture("dst", "rgba8", "ldr"));
    add(PassTypeBuilder("mipgen", "mip chain").input_texture("src", "any", "src").output_texture("dst", "rgba16f", "mips", {.mips = 0}));
    add(PassTypeBuilder("particles", "particle list").output_buffer("list", "16 B per pixel", {.bytes_per_pixel = 16}));
    add(PassTypeBuilder("counter", "counters").output_buffer("counts", "1 KiB", {.bytes = 1024}));
    add(PassTypeBuilder("volume", "a grid sized by its parameter")
            .param_int("grid", 8, 1, 64, "cells per side")
            .output_buffer("cells", "grid^3 floats",
                           {.from_params = [](const json& p) { return size_t(std::pow(p.at("grid").get<int>(), 3)) * 4; }}));
    add(PassTypeBuilder("draw", "draws a list")
            .input_buffer("list", "list")
            .input_buffer("counts", "counts", {.optional = true})
            .output_texture("color", "rgba8", "image"));
    add(PassTypeBuilder("anyout", "format chosen by the graph").output_texture("dst", "any", "dst"));
    add(PassTypeBuilder("mix", "mixes up to two inputs")
            .input_texture("a", "any", "a", {.optional = true})
            .input_texture("b", "any", "b", {.optional = true})
            .output_texture("dst", "rgba16f", "mixed"));
    // Values that must agree (graph_agree.cpp): a range's two ends, and a form a reader
    // shares with what wrote its input, through a pass in between.
    add(PassTypeBuilder("ranged", "a range of two parameters")
            .param_float("lo", 1.0, -1.0, 100.0, "lower end; <= 0: automatic", {.at_most = "hi", .automatic_at_or_below = 0.0})
            .param_float("hi", 2.0, -1.0, 100.0, "upper end; <= 0: automatic")
            .output_texture("dst", "rgba8", "out"));
    add(PassTypeBuilder("former", "writes in a form")
            .param_enum("form", "a", {"a", "b"}, "the form")
            .param_float("width", 1.0, 0.0, 10.0, "a width")
            .output_texture("dst", "rgba16f", "written in `form`"));
    add(PassTypeBuilder("reader", "reads in a form")
            .param_enum("form", "a", {"a", "b"}, "must be the writer's")
            .param_float("width", 1.0, 0.0, 10.0, "must be the writer's")
            .param_float("gain", 1.0, 0.0, 10.0, "its own")
            .input_texture("src", "any", "the former's output, maybe through others", {.same_params = {"*"}})
            .output_texture("dst", "rgba8", "read"));
    return reg;
}

}  // namespace

const PassRegistry& fake_registry() {
    static const PassRegistry reg = make();
    return reg;
}

GraphFile parse(const std::string& text) { return parse_graph_json(text, "test.json"); }

std::vector<Diagnostic> problems(const std::string& text) {
    try {
        return validate_graph(parse(text), fake_registry());
    } catch (const GraphError& e) {
        return e.diagnostics;
    }
}

CompiledGraph compile(const std::string& text, glm::ivec2 size) {
    return compile_graph(parse(text), fake_registry(), size);
}

std::string all(const std::vector<Diagnostic>& d) {
    std::string s;
    for (const auto& x : d) s += "  " + x.str() + "\n";
    return s.empty() ? "  (none)\n" : s;
}

::testing::AssertionResult has_problem(const std::vector<Diagnostic>& d, const std::string& pointer,
                                       const std::string& phrase) {
    for (const auto& x : d)
        if (x.pointer == pointer && x.message.find(phrase) != std::string::npos) {
            if (x.file != "test.json") return ::testing::AssertionFailure() << "wrong file in " << x.str();
            return ::testing::AssertionSuccess();
        }
    return ::testing::AssertionFailure() << "no problem at " << pointer << " containing '" << phrase << "'; got:\n" << all(d);
}

}  // namespace pathlet::test
