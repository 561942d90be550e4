// scripts/transparency-techniques.py, the one table of the transparency techniques (speed, bytes a pixel and
// fidelity of each technique against the exact reference), run as a user runs it on a small
// experiment: WBOIT and MBOIT against variant2_exact on the small phantom. The table must hold
// one row a technique with the reference's SSIM 1 and the others' in (0, 1), the bytes a pixel
// of the plan (WBOIT 24, MBOIT 32 with the coverage), and --plots must write the figure. A bad
// experiment file is exit status 2 with the file named.
#include "cli_run.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

CliRun script(const std::string& args) {
    return run_command(std::string("/usr/bin/python3 ") + PATHLET_SOURCE_DIR + "/scripts/transparency-techniques.py " +
                       args + " --pathlet " + PATHLET_CLI);
}

// The cells of the table row whose first cell is `name`.
std::vector<std::string> row(const std::string& table, const std::string& name) {
    std::istringstream in(table);
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("| " + name + " |", 0) != 0) continue;
        std::vector<std::string> cells;
        std::stringstream s(line.substr(2));
        std::string c;
        while (std::getline(s, c, '|')) {
            const size_t a = c.find_first_not_of(' '), b = c.find_last_not_of(' ');
            cells.push_back(a == std::string::npos ? "" : c.substr(a, b - a + 1));  // an empty cell too
        }
        return cells;
    }
    return {};
}

}  // namespace

TEST(TechniquesTable, OneRowATechniqueWithFidelityAndBytes) {
    const fs::path dir = fs::temp_directory_path() / ("pathlet_tt_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "exp.json") << R"({ "name": "tiny", "graphs": [ { "graph": "variant2_exact", "label": "exact" },
        { "graph": "variant2_wboit", "label": "WBOIT" }, { "graph": "variant2_mboit", "label": "MBOIT" } ],
      "data": [ { "phantom": "small" } ], "sizes": [ "640x360" ], "time": "2:2.04:0.04", "frames": 1, "warmup": 0,
      "set": [ "overlay=false", "window=0" ] })";
    const CliRun r = script((dir / "exp.json").string() + " --out " + (dir / "out").string() + " --plots");
    ASSERT_EQ(r.code, 0) << r.err;
    // technique | setting | size | frame ms | x exact | bytes/px | SSIM | PSNR | RMSE | > 8/255 % | flicker | FLIP | passes
    const auto exact = row(r.out, "exact"), wboit = row(r.out, "WBOIT"), mboit = row(r.out, "MBOIT");
    ASSERT_EQ(exact.size(), 13u) << r.out;
    ASSERT_EQ(wboit.size(), 13u) << r.out;
    ASSERT_EQ(mboit.size(), 13u) << r.out;
    EXPECT_EQ(exact[6], "1.0000");
    EXPECT_EQ(exact[11], "0.0000") << "FLIP of the reference against itself";
    for (const auto* t : {&wboit, &mboit}) {
        const double ssim = std::stod((*t)[6]);
        EXPECT_GT(ssim, 0.3) << (*t)[0];
        EXPECT_LT(ssim, 1.0) << (*t)[0] << ": an approximation is not the reference";
        EXPECT_GT(std::stod((*t)[3]), 0.0) << "frame ms";
        const double flip = std::stod((*t)[11]);
        EXPECT_GT(flip, 0.0) << (*t)[0] << ": FLIP sees the approximation";
        EXPECT_LT(flip, 1.0) << (*t)[0];
    }
    EXPECT_EQ(wboit[5], "24") << "20 bytes of sums and 4 of coverage a pixel";
    EXPECT_EQ(mboit[5], "32") << "b0, 4 moments, the colour sums and the coverage";
    EXPECT_NE(wboit[12].find("accum"), std::string::npos) << "per pass";
    for (const char* f : {"transparency_techniques.md", "transparency_techniques.csv", "transparency_techniques.png",
                          "transparency_techniques.svg"})
        EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
    fs::remove_all(dir);
}

TEST(TechniquesTable, ABadExperimentIsAUsageError) {
    const fs::path dir = fs::temp_directory_path() / ("pathlet_tt_bad_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "bad.json") << R"({ "name": "bad", "graphs": [] })";
    CliRun r = script((dir / "bad.json").string() + " --out " + (dir / "out").string());
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("bad.json: /graphs"), std::string::npos) << r.err;
    std::ofstream(dir / "broken.json") << "{ not json";
    r = script((dir / "broken.json").string());
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("broken.json"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out" / "transparency_techniques.md")) << "nothing written";
    fs::remove_all(dir);
}
