#include "fake_registry.hpp"
#include "util/input_limits.hpp"
#include "util/text.hpp"
#include <pathlet/text.hpp>

#include <filesystem>

#include <cstdio>
#include <fstream>

using namespace pathlet;
using namespace pathlet::test;

TEST(Parse, CommentsAndAllSectionsAreRead) {
    GraphFile g = parse(R"json(
    // a hand-written graph
    {
      "$schema": "../graphs/schema/pathlet-graph.schema.json",
      "version": 1, "name": "demo", "description": "all sections", /* block comment */
      "variables": {
        "radius": {"type": "float", "default": 1, "min": 0, "max": 4, "doc": "AO radius"},
        "mode": {"type": "enum", "default": "sphere", "choices": ["hemisphere", "sphere"]},
        "tint": {"type": "color", "default": "#ff0000"}
      },
      "resources": {
        "hdr": {"format": "rgba16f", "size": "output", "mips": "full", "history": true},
        "half": {"format": "r8", "size": {"relative_to": "hdr", "scale": [0.5, 0.25]}, "mips": 3},
        "fixed": {"format": "rgba8", "size": [64, 32], "persistent": true},
        "list": {"kind": "buffer", "bytes_per_pixel": 8},
        "counts": {"kind": "buffer", "bytes": 4096}
      },
      "passes": [
        {"name": "a", "type": "blur", "params": {"taps": 3}, "inputs": {"src": "hdr@prev"},
         "outputs": {"dst": "hdr"}, "enabled": "$on", "doc": "x"}
      ],
      "outputs": ["hdr", {"resource": "a.dst", "capture": "out/{graph}/{frame:05}.png"}]
    })json");
    EXPECT_EQ(g.name, "demo");
    EXPECT_EQ(g.description, "all sections");
    ASSERT_EQ(g.variables.size(), 3u);
    EXPECT_EQ(g.variables[1].name, "radius");  // objects come back in key order
    EXPECT_DOUBLE_EQ(g.variables[1].value.get<double>(), 1.0);
    EXPECT_EQ(g.variables[1].decl.max, 4.0);
    EXPECT_EQ(g.variables[0].decl.type, ParamType::Enum);
    EXPECT_EQ(g.variables[2].value, json::array({1.0, 0.0, 0.0}));  // coerced default
    ASSERT_EQ(g.resources.size(), 5u);
    const auto res = [&](const std::string& n) {
        for (const auto& r : g.resources)
            if (r.name == n) return r;
        ADD_FAILURE() << n;
        return ResourceDecl{};
    };
    EXPECT_EQ(res("hdr").mips, 0);
    EXPECT_TRUE(res("hdr").history);
    EXPECT_EQ(res("hdr").size->relative_to, "output");
    EXPECT_EQ(res("half").size->relative_to, "hdr");
    EXPECT_FLOAT_EQ(res("half").size->scale_x, 0.5f);
    EXPECT_FLOAT_EQ(res("half").size->scale_y, 0.25f);
    EXPECT_EQ(res("half").mips, 3);
    EXPECT_EQ(res("fixed").size->relative_to, "");
    EXPECT_EQ(res("fixed").size->width, 64);
    EXPECT_TRUE(res("fixed").persistent);
    EXPECT_EQ(res("list").kind, PinKind::Buffer);
    EXPECT_EQ(res("list").bytes_per_pixel, 8u);
    EXPECT_EQ(res("counts").bytes, 4096u);
    ASSERT_EQ(g.passes.size(), 1u);
    EXPECT_EQ(g.passes[0].inputs.at("src"), "hdr@prev");
    EXPECT_EQ(g.passes[0].enabled, "$on");
    EXPECT_EQ(g.passes[0].pointer, "/passes/0");
    ASSERT_EQ(g.outputs.size(), 2u);
    EXPECT_EQ(g.outputs[0].resource, "hdr");
    EXPECT_EQ(g.outputs[1].capture, "out/{graph}/{frame:05}.png");
    EXPECT_EQ(g.outputs[1].pointer, "/outputs/1");
}

namespace {
// The single diagnostic a text that does not parse as JSON gets (GraphError, never an escaping
// nlohmann exception).
Diagnostic json_error(const std::string& text) {
    try {
        parse(text);
    } catch (const GraphError& e) {
        EXPECT_EQ(e.diagnostics.size(), 1u) << e.what();
        EXPECT_EQ(std::string(e.what()).find("[json.exception"), std::string::npos) << e.what();
        return e.diagnostics.at(0);
    }
    ADD_FAILURE() << "no error for: " << text;
    return {};
}
}  // namespace

TEST(Parse, SyntaxErrorGivesLineAndColumn) {
    Diagnostic d = json_error("{\n  \"name\": \"x\",\n  \"passes\": [,]\n}");
    EXPECT_EQ(d.line, 3);
    EXPECT_EQ(d.column, 14);
    EXPECT_EQ(d.str().rfind("test.json:3:14: syntax error", 0), 0u) << d.str();
}

TEST(Parse, SyntaxErrorAfterACommentCountsItsLines) {
    EXPECT_EQ(json_error("// one\n// two\n{\"name\": tru}").line, 3);
}

// Found by fuzz_graph: nlohmann throws out_of_range (not parse_error) for 1e400.
TEST(Parse, NumberBeyondDoubleIsAGraphErrorWithItsPlace) {
    Diagnostic d = json_error("{\n  \"name\": \"x\",\n  \"version\": 1e400\n}");
    EXPECT_EQ(d.line, 3);
    EXPECT_EQ(d.column, 14);
    EXPECT_NE(d.message.find("'1e400'"), std::string::npos) << d.str();
}

// Casting 1e300 to int64 or float is undefined behaviour; both are refused with a message.
TEST(Parse, HugeIntDefaultAndScaleAreRefused) {
    auto d = problems(R"json({
      "variables": {"n": {"type": "int", "default": 1e300}},
      "resources": {"r": {"size": {"relative_to": "output", "scale": 1e300}}}
    })json");
    EXPECT_TRUE(has_problem(d, "/variables/n/default", "64-bit integer"));
    EXPECT_TRUE(has_problem(d, "/resources/r/size/scale", "at most 1e6"));
}

TEST(Parse, UnknownKeysSuggestTheClosest) {
    auto d = problems(R"json({
      "pases": [],
      "resources": {"hdr": {"fromat": "rgba16f"}},
      "passes": [{"name": "a", "type": "blur", "param": {}}],
      "outputs": [{"resource": "a.dst", "captur": "x.png"}],
      "variables": {"v": {"type": "float", "defualt": 1}}
    })json");
    EXPECT_TRUE(has_problem(d, "/pases", "unknown top-level key 'pases' (did you mean 'passes'?)"));
    EXPECT_TRUE(has_problem(d, "/resources/hdr/fromat", "did you mean 'format'?"));
    EXPECT_TRUE(has_problem(d, "/passes/0/param", "did you mean 'params'?"));
    EXPECT_TRUE(has_problem(d, "/outputs/0/captur", "did you mean 'capture'?"));
    EXPECT_TRUE(has_problem(d, "/variables/v/defualt", "did you mean 'default'?"));
}

TEST(Parse, StructureErrorsAreAllCollected) {
    auto d = problems(R"json({
      "version": 2,
      "variables": {"r": {"type": "float", "default": 9, "max": 4}, "e": {"type": "enum", "default": "a"},
                    "t": {"type": "flaot", "default": 1}},
      "resources": {
        "a": {"format": "rgba16"},
        "b": {"format": "r8", "size": {"relative_to": "a", "scale": 0}},
        "c": {"format": "r8", "size": [0, 10]},
        "d": {"format": "r8", "mips": "fulll"},
        "e": {"kind": "buffer", "format": "r8"},
        "f": {"kind": "bufer"},
        "g.h": {"format": "r8"},
        "i": {"bytes": 16}
      },
      "passes": [{"type": "blur"}, {"name": "x", "type": "blur", "enabled": "yes", "inputs": {"src": 3}}],
      "outputs": {}
    })json");
    EXPECT_TRUE(has_problem(d, "/version", "newer than this engine"));
    EXPECT_TRUE(has_problem(d, "/variables/r/default", "out of range"));
    EXPECT_TRUE(has_problem(d, "/variables/e", "needs \"choices\""));
    EXPECT_TRUE(has_problem(d, "/variables/t/type", "did you mean 'float'?"));
    EXPECT_TRUE(has_problem(d, "/resources/a/format", "unknown format 'rgba16' (did you mean 'rgba16f'?)"));
    EXPECT_TRUE(has_problem(d, "/resources/b/size/scale", "positive"));
    EXPECT_TRUE(has_problem(d, "/resources/c/size", "positive integers"));
    EXPECT_TRUE(has_problem(d, "/resources/d/mips", "\"full\""));
    EXPECT_TRUE(has_problem(d, "/resources/e/format", "applies to textures"));
    EXPECT_TRUE(has_problem(d, "/resources/f/kind", "did you mean 'buffer'?"));
    EXPECT_TRUE(has_problem(d, "/resources/g.h", "must not contain '.'"));
    EXPECT_TRUE(has_problem(d, "/resources/i/bytes", "applies to buffers"));
    EXPECT_TRUE(has_problem(d, "/passes/0", "needs a \"name\""));
    EXPECT_TRUE(has_problem(d, "/passes/1/enabled", "\"$variable\""));
    EXPECT_TRUE(has_problem(d, "/passes/1/inputs/src", "must name"));
    EXPECT_TRUE(has_problem(d, "/outputs", "must be an array"));
    EXPECT_GE(d.size(), 16u);
}

TEST(Parse, ReadsFilesAndNamesMissingOnes) {
    const std::string path = std::string(PATHLET_TEST_BINARY_DIR) + "/parse_test_graph.json";
    {
        std::ofstream f(path);
        f << "// file\n{\"name\": \"from_file\", \"passes\": [], \"outputs\": []}\n";
    }
    GraphFile g = parse_graph_file(path);
    EXPECT_EQ(g.name, "from_file");
    EXPECT_EQ(g.path, path);
    std::remove(path.c_str());
    try {
        parse_graph_file(path);
        FAIL();
    } catch (const GraphError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
    }
}

TEST(DidYouMean, ClosestWithinARelativeDistance) {
    const std::vector<std::string> c = {"radius", "samples", "mode", "tonemap", "bloom"};
    EXPECT_EQ(text::closest_match("raduis", c), "radius");   // transposition counts once
    EXPECT_EQ(text::closest_match("sampels", c), "samples");
    EXPECT_EQ(text::closest_match("RADIUS", c), "radius");
    EXPECT_EQ(text::closest_match("tonemp", c), "tonemap");
    EXPECT_EQ(text::closest_match("blur", c), "");           // too far for a short word
    EXPECT_EQ(text::closest_match("xyz", c), "");
    EXPECT_EQ(text::closest_match("x", {}), "");
}

TEST(Parse, DeepNestingIsRefusedBeforeItCanOverflowTheStack) {
    // A wrongly typed value nested 100k deep crashed validate when the message printed it.
    std::string deep = "{\"version\": 1, \"passes\": " + std::string(100000, '[') + std::string(100000, ']') + "}";
    try {
        pathlet::parse_graph_json(deep, "deep.json");
        FAIL() << "a 100k-deep graph must be refused";
    } catch (const pathlet::GraphError& e) {
        ASSERT_EQ(e.diagnostics.size(), 1u);
        EXPECT_EQ(e.diagnostics[0].file, "deep.json");
        EXPECT_NE(e.diagnostics[0].message.find("nesting deeper than"), std::string::npos);
        EXPECT_EQ(e.diagnostics[0].line, 1);
    }
    std::string params = "{\"version\": 1, \"passes\": [{\"name\": \"a\", \"type\": \"t\", \"params\": {\"x\": " +
                         std::string(50000, '[') + std::string(50000, ']') + "}}]}";
    EXPECT_THROW(pathlet::parse_graph_json(params, "params.json"), pathlet::GraphError);
    // Brackets inside strings and comments do not count.
    std::string text = "// [[[[\n{\"version\": 1, \"name\": \"" + std::string(500, '[') + "\"}";
    EXPECT_EQ(pathlet::io::json_nesting_depth(text, 128).depth, 1);
}

TEST(Parse, ADirectoryIsNotAGraphFile) {
    try {
        pathlet::parse_graph_file(std::filesystem::temp_directory_path().string());
        FAIL();
    } catch (const pathlet::GraphError& e) {
        EXPECT_NE(e.diagnostics.at(0).message.find("is a directory"), std::string::npos) << e.diagnostics[0].message;
    }
}
