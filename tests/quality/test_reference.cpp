// `pathlet quality GRAPH --reference REFGRAPH` end to end (issue 42), through the command on
// llvmpipe: the exact reference against depth peeling agrees (ssim 1 within float noise, no
// pixel over 8/255), the study's variant 2 (AO multiplied in, 32 fragments) does not, --out
// gets one difference image and one FLIP image per frame and the last pictures, WBOIT has a FLIP
// against the exact reference, and bad use is an error naming it.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

namespace fs = std::filesystem;

namespace {

struct CliRun {
    int rc = -1;
    std::string out;
    std::map<std::string, double> v;  // "ssim", "psnr", "rmse", "share", "flip", "flip_all", "flicker"
};

CliRun quality(const std::string& args) {
    const std::string cmd = std::string(PATHLET_CLI) + " quality " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    CliRun r;
    char line[1024];
    while (p && fgets(line, sizeof line, p)) {
        r.out += line;
        const std::string s(line);
        for (const auto& [key, prefix] : std::map<std::string, std::string>{{"ssim", "ssim "},
                                                                             {"psnr", "psnr "},
                                                                             {"rmse", "rmse "},
                                                                             {"share", "share over 8/255 "},
                                                                             {"flip", "flip "},
                                                                             {"flicker", "flicker vs reference "}})
            if (s.rfind(prefix, 0) == 0 && s.compare(prefix.size(), 3, "n/a") != 0)
                r.v[key] = std::stod(s.substr(prefix.size()));
        if (const size_t all = s.find("all pixels "); s.rfind("flip ", 0) == 0 && all != std::string::npos)
            r.v["flip_all"] = std::stod(s.substr(all + 11));
    }
    const int st = p ? pclose(p) : -1;
    r.rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return r;
}

const std::string kCommon = " --phantom small --size 160x90 --time 2:2.08:0.04 --set overlay=false";

}  // namespace

TEST(QualityReference, ExactAgainstDepthPeelingAgreesAndWritesTheDifferenceImages) {
    const fs::path out = fs::path(PATHLET_TEST_BINARY_DIR) / "quality_reference_out";
    fs::remove_all(out);
    const CliRun r = quality("variant2_exact --reference variant2_depth_peel" + kCommon + " --out " + out.string());
    ASSERT_EQ(r.rc, 0) << r.out;
    ASSERT_EQ(r.v.size(), 7u) << r.out;
    EXPECT_GT(r.v.at("ssim"), 0.9999) << r.out;
    EXPECT_LT(r.v.at("rmse"), 1.0 / 255.0) << r.out;
    EXPECT_EQ(r.v.at("share"), 0.0) << r.out;
    EXPECT_LT(r.v.at("flip"), 0.01) << r.out;
    EXPECT_LT(r.v.at("flicker"), 0.5 / 255.0) << r.out;
    EXPECT_NE(r.out.find("variant2_exact vs variant2_depth_peel: 3 frames 160x90"), std::string::npos) << r.out;
    for (const char* f : {"variant2_exact_vs_variant2_depth_peel_diff_00000.png",
                          "variant2_exact_vs_variant2_depth_peel_diff_00002.png",
                          "variant2_exact_vs_variant2_depth_peel_flip_00000.png",
                          "variant2_exact_vs_variant2_depth_peel_flip_00002.png", "variant2_exact_last.png",
                          "variant2_depth_peel_last.png"})
        EXPECT_TRUE(fs::exists(out / f)) << f << "\n" << r.out;
    EXPECT_FALSE(fs::exists(out / "variant2_exact_vs_variant2_depth_peel_diff_00003.png"));
}

// The study's variant 2 multiplies LineAO into the colour and keeps 32 fragments: not the
// reference's picture, and every measure says so.
TEST(QualityReference, TheStudysVariant2IsFarFromTheReference) {
    const CliRun r = quality("variant2_oit --reference variant2_exact" + kCommon);
    ASSERT_EQ(r.rc, 0) << r.out;
    EXPECT_LT(r.v.at("ssim"), 0.99) << r.out;
    EXPECT_GT(r.v.at("rmse"), 2.0 / 255.0) << r.out;
    EXPECT_LT(r.v.at("psnr"), 45.0) << r.out;
    EXPECT_GT(r.v.at("share"), 0.5) << r.out;  // percent
    EXPECT_GT(r.v.at("flip"), 0.02) << r.out;
    EXPECT_GT(r.v.at("flicker"), 0.0) << r.out;
}

// WBOIT blends without order: FLIP sees it, over the covered pixels more than over the whole
// frame (the background agrees), and less from further away (more pixels per degree).
TEST(QualityReference, WboitHasAFlipAgainstTheExactReference) {
    const CliRun r = quality("variant2_wboit --reference variant2_exact" + kCommon);
    ASSERT_EQ(r.rc, 0) << r.out;
    ASSERT_TRUE(r.v.count("flip") && r.v.count("flip_all")) << r.out;
    EXPECT_GT(r.v.at("flip"), 0.005) << r.out;
    EXPECT_LT(r.v.at("flip"), 0.5) << r.out;
    EXPECT_GT(r.v.at("flip"), 2.0 * r.v.at("flip_all")) << r.out;
    EXPECT_NE(r.out.find("67.0 pixels per degree"), std::string::npos) << r.out;
    const CliRun far = quality("variant2_wboit --reference variant2_exact --ppd 200" + kCommon);
    ASSERT_EQ(far.rc, 0) << far.out;
    EXPECT_LT(far.v.at("flip"), r.v.at("flip")) << far.out;
    EXPECT_NE(far.out.find("200.0 pixels per degree"), std::string::npos) << far.out;
}

TEST(QualityReference, BadUseIsAnErrorNamingIt) {
    CliRun r = quality("variant2_exact --reference no_such_graph" + kCommon);
    EXPECT_EQ(r.rc, 2) << r.out;
    EXPECT_NE(r.out.find("no_such_graph"), std::string::npos) << r.out;
    r = quality("variant2_exact --reference variant2_depth_peel --ppd 0" + kCommon);
    EXPECT_EQ(r.rc, 2) << r.out;
    EXPECT_NE(r.out.find("--ppd"), std::string::npos) << r.out;
    r = quality("variant2_exact --ppd 60 --transparency" + kCommon);
    EXPECT_EQ(r.rc, 2) << r.out;
    EXPECT_NE(r.out.find("ppd"), std::string::npos) << r.out;
    r = quality("variant2_exact --reference variant2_depth_peel --transparency" + kCommon);
    EXPECT_EQ(r.rc, 2) << r.out;
    EXPECT_NE(r.out.find("--reference"), std::string::npos) << r.out;
    // A graph without coverage to measure over (no wall depth, no line pass depth output).
    r = quality("demo_blur --reference variant2_exact" + kCommon);
    EXPECT_NE(r.rc, 0) << r.out;
    EXPECT_NE(r.out.find("no coverage"), std::string::npos) << r.out;
}

// The coverage is searched past passes without "outputs": here the first pass (clear_list, its
// outputs implicit resources) has none, and there is no wall; fill_list's coverage is found.
TEST(QualityReference, AFirstPassWithoutOutputsDoesNotEndTheCoverageSearch) {
    const fs::path g = fs::path(PATHLET_TEST_BINARY_DIR) / "quality_no_outputs_first.json";
    std::ofstream(g) << R"({"version": 1, "name": "no_outputs_first",
  "resources": {"nodes": {"kind": "buffer"}, "coverage": {"format": "depth24"}, "color": {"format": "rgba8"}},
  "passes": [
    {"name": "clear_list", "type": "clear_list"},
    {"name": "fill_list", "type": "fill_list", "params": {"never_drop": true},
     "inputs": {"heads": "clear_list.heads", "counter": "clear_list.counter"},
     "outputs": {"nodes": "nodes", "coverage": "coverage"}},
    {"name": "resolve", "type": "resolve_exact",
     "inputs": {"heads": "clear_list.heads", "nodes": "nodes", "coverage": "coverage"}, "outputs": {"color": "color"}}],
  "outputs": [{"resource": "color"}]})";
    const CliRun r = quality(g.string() + " --reference variant2_exact --phantom small --size 160x90 --time 2");
    ASSERT_EQ(r.rc, 0) << r.out;
    EXPECT_NE(r.out.find("no_outputs_first vs variant2_exact"), std::string::npos) << r.out;
    EXPECT_TRUE(r.v.count("ssim")) << r.out;
}

// Nothing to measure is no score: at 8x8 no 11x11 SSIM window lies inside the picture, so
// ssim is n/a and the command fails (exit 2), never "ssim 1.00000" and PSNR infinity.
TEST(QualityReference, NothingToMeasureIsNotAPerfectScore) {
    const CliRun r = quality("variant2_wboit --reference variant2_exact --phantom small --size 8x8 --time 2");
    EXPECT_EQ(r.rc, 2) << r.out;
    EXPECT_NE(r.out.find("ssim n/a"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("ssim 1.0"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("psnr inf"), std::string::npos) << r.out;
}
