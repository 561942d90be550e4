// Experiment files and viewer scripts get the limits graph files get: size, nesting
// and numbers, with errors naming the file and the place; the fuzz regressions of their readers
// and of the plugin ELF check replay here too, without the fuzz build.
#include "bench/experiment.hpp"
#include "../support/error_text.hpp"
#include "util/text.hpp"
#include "view/view_script.hpp"

#include <pathlet/scene.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

using namespace pathlet;
namespace fs = std::filesystem;

namespace {

std::string data_error(const std::function<void()>& f) { return test::error_text<DataError>(f); }

std::string experiment_error(const std::string& text) {
    return data_error([&] { cli::bench::parse_experiment(text::parse_json_of("e.json", text, "experiment file"), "e.json"); });
}

std::string script_error(const std::string& text) {
    return data_error([&] { view::parse_script(text, "s.json"); });
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(ExperimentFile, NumbersHaveCaps) {
    EXPECT_NE(experiment_error(R"({"graphs": ["isl"], "frames": 1000000000})").find("e.json: /frames: expected an integer >= 1 and <= 100000"),
              std::string::npos);
    EXPECT_NE(experiment_error(R"({"graphs": ["isl"], "warmup": -1})").find("/warmup"), std::string::npos);
    EXPECT_NE(experiment_error(R"({"graphs": ["isl"], "sizes": ["99999999999x1"]})").find("/sizes/0: expected WxH"),
              std::string::npos);
    EXPECT_NE(experiment_error(R"({"graphs": ["isl"], "sizes": ["20000x10"]})").find("(1..16384)"), std::string::npos);
    EXPECT_NE(experiment_error(R"({"graphs": ["isl"], "time": 1e400})").find("e.json:1:29: not valid JSON (experiment file): number out of range"),
              std::string::npos)
        << experiment_error(R"({"graphs": ["isl"], "time": 1e400})");
    EXPECT_NE(experiment_error("{\"graphs\": " + std::string(1000, '[') + std::string(1000, ']') + "}").find("nesting deeper than"),
              std::string::npos);
    EXPECT_EQ(experiment_error(R"({"graphs": ["isl"], "frames": 5, "sizes": ["16384x16384"]})"), "");
}

TEST(ViewScript, EventsAreCheckedWithTheirPointer) {
    EXPECT_NE(script_error(R"([{"frame": 0, "drag": [1, 2], "button": 5}])").find("s.json:/0: \"button\" must be left, right or middle"),
              std::string::npos);
    EXPECT_NE(script_error(R"([{"frame": 2000000000, "key": "space"}])").find("s.json:/0: an event needs \"frame\""),
              std::string::npos);
    EXPECT_NE(script_error("[" + std::string(500, '[') + "]").find("nesting deeper than"), std::string::npos);
    EXPECT_EQ(view::parse_script(R"([{"frame": 3, "drag": [4, 0]}])", "s.json").at(0).button, "left");
}

TEST(FuzzRegressions, ExperimentAndViewScriptInputsAreErrorsNotCrashes) {
    const fs::path dir = fs::path(PATHLET_SOURCE_DIR) / "tests" / "fuzz" / "regressions";
    size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir / "experiment")) {
        EXPECT_NE(experiment_error(slurp(e.path())), "") << e.path();
        ++n;
    }
    for (const auto& e : fs::directory_iterator(dir / "view_script")) {
        EXPECT_NE(script_error(slurp(e.path())), "") << e.path();
        ++n;
    }
    EXPECT_GE(n, 4u);
}
