// The command-line parser: options bound to typed variables; a malformed or unknown option is
// a UsageError naming it (exit 2 in main), a bad declaration a DeclarationError (a bug).
#include "args.hpp"
#include "renderer.hpp"

#include <gtest/gtest.h>

#include <optional>

using namespace pathlet;
using namespace pathlet::cli;

namespace {

std::string usage_error(Args& a, const std::vector<std::string>& argv) {
    try {
        a.parse(argv);
    } catch (const UsageError& e) {
        return e.what();
    }
    return "";
}

struct Bound {
    std::string graph, name = "x";
    std::optional<double> time;
    glm::ivec2 size{1280, 720};
    long frames = 10;
    float scale = 1.0f;
    Given<int> warmup{3};
    std::vector<std::string> sets;
    bool quiet = false;
    Args a{"demo", "a demo command"};
    Bound() {
        a.positional("GRAPH", graph, "graph", false)
            .option("time", time, "T", "start time")
            .option("size", size, "WxH", "output size")
            .option("frames", frames, "N", "frames")
            .option("scale", scale, "S", "scale")
            .option("warmup", warmup, "N", "warm-up frames")
            .option("name", name, "NAME", "a name")
            .short_name('n')
            .multi("set", sets, "NAME=VALUE", "overrides")
            .flag("quiet", quiet, "no output");
    }
};

}  // namespace

TEST(Args, ValuesArriveTypedInTheirVariables) {
    Bound b;
    ASSERT_TRUE(b.a.parse({"g.json", "--time", "9.5", "--size=64x32", "--frames", "3", "--set", "a=1", "-n", "y",
                           "--set", "b=2", "--quiet", "--warmup", "0"}));
    EXPECT_EQ(b.graph, "g.json");
    ASSERT_TRUE(b.time.has_value());
    EXPECT_DOUBLE_EQ(*b.time, 9.5);
    EXPECT_EQ(b.size, glm::ivec2(64, 32));
    EXPECT_EQ(b.frames, 3);
    EXPECT_EQ(b.name, "y");
    EXPECT_EQ(b.sets, (std::vector<std::string>{"a=1", "b=2"}));
    EXPECT_TRUE(b.quiet);
    EXPECT_EQ(b.warmup.value, 0);
    EXPECT_TRUE(b.warmup.given) << "given on the command line, even with the default's value";
}

TEST(Args, AbsentOptionsKeepTheirDefaults) {
    Bound b;
    ASSERT_TRUE(b.a.parse({}));
    EXPECT_FALSE(b.time.has_value());
    EXPECT_EQ(b.size, glm::ivec2(1280, 720));
    EXPECT_EQ(b.warmup.value, 3);
    EXPECT_FALSE(b.warmup.given);
    EXPECT_FALSE(b.quiet);
    const std::string help = b.a.help();
    EXPECT_NE(help.find("--size WxH\n      output size [default: 1280x720]"), std::string::npos) << help;
    EXPECT_NE(help.find("--warmup N\n      warm-up frames [default: 3]"), std::string::npos) << help;
    EXPECT_NE(help.find("-n, --name NAME"), std::string::npos) << help;
}

TEST(Args, MalformedValuesAreUsageErrorsNamingTheOption) {
    // `view --time x` used to fail with "stod": the option and the value are named now.
    for (const auto& [argv, want] : std::vector<std::pair<std::vector<std::string>, std::string>>{
             {{"--time", "x"}, "--time expects a number, got 'x'"},
             {{"--time", "9s"}, "--time expects a number, got '9s'"},
             {{"--time", ""}, "--time expects a number, got ''"},
             {{"--time", "nan"}, "--time expects a finite number, got 'nan'"},
             {{"--frames", "2.5"}, "--frames expects an integer, got '2.5'"},
             {{"--frames", "99999999999999999999"}, "--frames expects an integer"},
             {{"--warmup", "three"}, "--warmup expects an integer, got 'three'"},
             {{"--scale", "1e39"}, "--scale expects a number within a float's range"},
             {{"--size", "10by10"}, "--size '10by10': expected WIDTHxHEIGHT"},
             {{"--time"}, "--time needs a value (T)"},
             {{"--quiet=1"}, "--quiet takes no value"},
         }) {
        Bound b;
        const std::string e = usage_error(b.a, argv);
        EXPECT_EQ(e.rfind(want, 0), 0u) << "got: " << e << "\nwant: " << want;
    }
}

TEST(Args, UnknownOptionsAndArgumentsAreUsageErrorsWithAHint) {
    Bound b;
    EXPECT_EQ(usage_error(b.a, {"--tiem", "1"}), "unknown option --tiem (did you mean --time?)");
    EXPECT_EQ(usage_error(b.a, {"--fra", "1"}), "unknown option --fra (did you mean --frames?)");  // a prefix
    EXPECT_EQ(usage_error(b.a, {"--colour", "red"}), "unknown option --colour");
    EXPECT_EQ(usage_error(b.a, {"-x"}), "unknown option -x");
    EXPECT_EQ(usage_error(b.a, {"a.json", "b.json"}), "unexpected argument 'b.json'");
    std::string file;
    Args required("req", "");
    required.positional("FILE", file, "a file");
    EXPECT_EQ(usage_error(required, {}), "missing FILE");
}

TEST(Args, RestTakesEveryPositionalAmongTheOptions) {
    std::vector<std::string> files, sets;
    Args a("validate", "");
    a.rest("GRAPH", files, "graphs").multi("set", sets, "NAME=VALUE", "");
    ASSERT_TRUE(a.parse({"a.json", "--set", "x=1", "b.json", "--", "--odd.json"}));
    EXPECT_EQ(files, (std::vector<std::string>{"a.json", "b.json", "--odd.json"}));
    EXPECT_EQ(sets, (std::vector<std::string>{"x=1"}));
    std::vector<std::string> none;
    Args b("validate", "");
    b.rest("GRAPH", none, "graphs");
    EXPECT_EQ(usage_error(b, {}), "missing GRAPH");
}

TEST(Args, BadDeclarationsAreProgrammingErrors) {
    std::string s1, s2;
    bool f = false;
    EXPECT_THROW(Args("c", "").option("size", s1, "X", "").option("size", s2, "X", ""), DeclarationError);
    EXPECT_THROW(Args("c", "").option("a", s1, "X", "").short_name('o').option("b", s2, "X", "").short_name('o'),
                 DeclarationError);
    EXPECT_THROW(Args("c", "").flag("help", f, ""), DeclarationError) << "--help is built in";
    EXPECT_THROW(Args("c", "").flag("--quiet", f, ""), DeclarationError) << "names are given without dashes";
    std::vector<std::string> rest;
    EXPECT_THROW(Args("c", "").rest("A", rest, "").positional("B", s1, ""), DeclarationError);
    EXPECT_THROW(Args("c", "").positional("A", s1, "", false).positional("B", s2, ""), DeclarationError);
    EXPECT_FALSE((std::is_base_of_v<DeclarationError, UsageError>)) << "a bad command line is not a bug";
}

TEST(Args, TimeRangesAndTimingBackendsConvertWithTheirOwnMessages) {
    TimeRange t;
    TimingBackend tb = TimingBackend::Auto;
    Args a("render", "");
    a.option("time", t, "T", "").option("timing", tb, "B", "");
    ASSERT_TRUE(a.parse({"--time", "1:2:0.5", "--timing", "finish"}));
    EXPECT_EQ(t.times(), (std::vector<double>{1.0, 1.5, 2.0}));
    EXPECT_EQ(tb, TimingBackend::CpuFinish);
    EXPECT_EQ(usage_error(a, {"--time", "5:1"}), "--time '5:1': END is before START");
    EXPECT_EQ(usage_error(a, {"--timing", "fast"}), "--timing expects auto, gpu, finish or cpu, got 'fast'");
}
