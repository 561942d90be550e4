// The temporally stable variant against variant 1 on a small animated scene, through
// `pathlet quality` on llvmpipe: less flicker, no worse error against the ray-traced AO.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace {
struct Measures {
    double flicker = -1, mae = -1, correlation = -2;
};

Measures quality(const std::string& graph) {
    const std::string cmd = std::string(PATHLET_CLI) + " quality " + graph +
                            " --phantom small --size 160x90 --time 2:2.2:0.04 --rays 64 --flicker-rays 0 --out " +
                            PATHLET_TEST_BINARY_DIR + "/quality_out 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    Measures m;
    std::string all;
    char line[512];
    while (p && fgets(line, sizeof line, p)) {
        all += line;
        std::string s(line);
        if (auto at = s.find("mean |dAO| "); at != std::string::npos) m.flicker = std::stod(s.substr(at + 11));
        if (auto at = s.find("MAE "); at != std::string::npos) m.mae = std::stod(s.substr(at + 4));
        if (auto at = s.find("correlation "); at != std::string::npos) m.correlation = std::stod(s.substr(at + 12));
    }
    const int rc = p ? pclose(p) : -1;
    EXPECT_EQ(rc, 0) << all;
    EXPECT_GE(m.flicker, 0.0) << all;
    EXPECT_GE(m.mae, 0.0) << all;
    return m;
}
}  // namespace

TEST(StableVariant, FlickersLessThanVariant1AtNoWorseError) {
    const Measures v1 = quality(std::string(PATHLET_SOURCE_DIR) + "/graphs/variant1_lineao.json");
    const Measures st = quality(std::string(PATHLET_SOURCE_DIR) + "/graphs/variant1_stable.json");
    EXPECT_GT(v1.flicker, 0.0) << "the animated scene must flicker under variant 1";
    EXPECT_LT(st.flicker, 0.75 * v1.flicker);
    EXPECT_LE(st.mae, v1.mae * 1.05);
    EXPECT_GT(st.correlation, 0.0);
}

// The object-space AO, per pixel and per OIT fragment (its front layer), is much
// closer to the ray-traced AO than LineAO on the same frames.
TEST(VolumeAoVariants, CloserToTheRayTracedAoThanLineAo) {
    const Measures lineao = quality(std::string(PATHLET_SOURCE_DIR) + "/graphs/variant1_lineao.json");
    for (const char* g : {"variant1_vao", "variant2_oit_vao"}) {
        const Measures vao = quality(std::string(PATHLET_SOURCE_DIR) + "/graphs/" + g + ".json");
        EXPECT_LT(vao.mae, 0.12) << g;
        EXPECT_LT(vao.mae, 0.6 * lineao.mae) << g;
        EXPECT_GT(vao.correlation, 0.8) << g;
        EXPECT_GT(vao.correlation, lineao.correlation + 0.2) << g;
    }
}

TEST(StableVariant, IslHasNoAoToMeasure) {
    const std::string cmd = std::string(PATHLET_CLI) + " quality isl --phantom small --size 64x36 --time 2:2.08 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    std::string all;
    char line[512];
    while (p && fgets(line, sizeof line, p)) all += line;
    EXPECT_EQ(p ? pclose(p) : -1, 0);
    EXPECT_NE(all.find("not measured"), std::string::npos) << all;
}
