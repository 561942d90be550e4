// Figures framed for a paper, measured from the PNGs `pathlet render` writes: at the
// default camera the data fills at least 80 % of the frame's limiting dimension, and through a
// full --orbit every frame keeps it whole (no pixel of data on the border) and still fills 80 %.
// The phantom always; with ../shared/data/real a compact data set (aneurysm pathlines, whose
// bounding sphere is much larger than what they show) and a tall vessel with its wall (VMTK's
// abdominal aorta).
#include "cli_run.hpp"
#include "image_io.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

using namespace pathlet;

namespace {

struct Fill {
    double fill = 0;      // the data's box over the frame, in the limiting dimension
    bool border = false;  // a pixel of data in the outermost rows or columns
};

// Data: pixels more than 8 levels from the background (the top-left pixel; no overlay drawn).
Fill measure(const Image& im) {
    int x0 = im.width, y0 = im.height, x1 = -1, y1 = -1;
    Fill f;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            float d = 0;
            for (int c = 0; c < 3; ++c) d = std::max(d, std::fabs(im.at(x, y, c) - im.at(0, 0, c)));
            if (d <= 8.0f / 255.0f) continue;
            x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
            f.border |= x == 0 || y == 0 || x == im.width - 1 || y == im.height - 1;
        }
    if (x1 >= 0) f.fill = std::max(double(x1 - x0 + 1) / im.width, double(y1 - y0 + 1) / im.height);
    return f;
}

// Renders `args` (lines whole, no overlay) and measures every frame written.
std::vector<Fill> frames(const std::string& name, const std::string& args) {
    const fs::path out = fs::path(PATHLET_TEST_BINARY_DIR) / "framing" / name;
    fs::remove_all(out);
    const CliRun r = pathlet_cli("render variant1_lineao " + args +
                                 " --size 320x180 --set window=-1 --set overlay=false --quiet --out " + out.string());
    EXPECT_EQ(r.code, 0) << r.err;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(out / "variant1_lineao"))
        if (e.path().extension() == ".png") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    std::vector<Fill> fills;
    for (const auto& f : files) fills.push_back(measure(read_image(f.string())));
    return fills;
}

// The default camera at one time, and a full turn: 16 frames 0.25 s apart at 90 degrees a
// second, 22.5 degrees between frames.
void expect_framed(const std::string& name, const std::string& data) {
    const std::vector<Fill> still = frames(name + "_default", data + " --time 1");
    ASSERT_EQ(still.size(), 1u);
    EXPECT_GE(still[0].fill, 0.8) << name << ": the default camera leaves the data small";
    EXPECT_FALSE(still[0].border) << name << ": the default camera cuts the data";
    const std::vector<Fill> turn = frames(name + "_orbit", data + " --time 0:3.75:0.25 --orbit 90");
    ASSERT_EQ(turn.size(), 16u);
    for (size_t i = 0; i < turn.size(); ++i) {
        EXPECT_FALSE(turn[i].border) << name << ": orbit frame " << i << " (" << 22.5 * double(i) << " degrees) cuts the data";
        EXPECT_GE(turn[i].fill, 0.8) << name << ": orbit frame " << i << " leaves the data small";
        EXPECT_LE(turn[i].fill, 0.97) << name << ": orbit frame " << i;
    }
}

std::string real(const std::string& rel) {
    const char* env = std::getenv("PATHLET_REAL_DATA_DIR");
    const std::string path = env && *env ? std::string(env) + "/" + rel : "";
    return !path.empty() && fs::exists(path) ? path : "";
}

}  // namespace

TEST(Framing, PhantomFillsTheFrameAndStaysWholeThroughAnOrbit) { expect_framed("phantom", "--phantom small"); }

TEST(Framing, CompactRealDataFillsTheFrame) {
    const std::string path = real("aneurysm-pathlines/blood_flow");
    if (path.empty()) GTEST_SKIP() << "real data absent (PATHLET_REAL_DATA_DIR/aneurysm-pathlines)";
    expect_framed("aneurysm", "--data " + path);
}

TEST(Framing, TallVesselWithItsWallFillsTheFrame) {
    const std::string lines = real("vmtk-abdominal-aorta/aorta-centerline.vtp");
    const std::string wall = real("vmtk-abdominal-aorta/aorta-surface.stl");
    if (lines.empty() || wall.empty()) GTEST_SKIP() << "real data absent (PATHLET_REAL_DATA_DIR/vmtk-abdominal-aorta)";
    expect_framed("vmtk", "--data " + lines + " --streamlines --mesh " + wall);
}

namespace {

struct Box {
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
    bool empty() const { return x1 < 0; }
    void add(int x, int y) { x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y); }
};

// The phantom at t = 1 s with and without the overlay, and the timing table's text.
struct Shot {
    Image with, without;
    std::string table;
};
Shot shot(const std::string& name, const std::string& size) {
    const fs::path out = fs::path(PATHLET_TEST_BINARY_DIR) / "framing" / name;
    fs::remove_all(out);
    Shot s;
    for (const bool overlay : {true, false}) {
        const fs::path dir = out / (overlay ? "with" : "without");
        const CliRun r = pathlet_cli("render variant1_lineao --phantom small --time 1 --quiet --size " + size +
                                     (overlay ? "" : " --set overlay=false") + " --out " + dir.string());
        EXPECT_EQ(r.code, 0) << r.err;
        (overlay ? s.with : s.without) = read_image((dir / "variant1_lineao" / "00000.png").string());
        if (overlay) s.table = r.out;
    }
    return s;
}

double stat(const std::string& table, const std::string& name) {
    const size_t at = table.find(name + " ");
    return at == std::string::npos ? -1.0 : std::stod(table.substr(at + name.size() + 1));
}

}  // namespace

// The legend stands beside the data (not at the frame's edge) and is labelled with 3 to 5
// round values inside the colour map's range.
TEST(Framing, LegendStandsBesideTheDataWithRoundTicks) {
    const Shot s = shot("legend", "480x270");
    Box data, legend;
    for (int y = 0; y < s.with.height; ++y)
        for (int x = 0; x < s.with.width; ++x) {
            float bg = 0, ov = 0;
            for (int c = 0; c < 3; ++c) {
                bg = std::max(bg, std::fabs(s.without.at(x, y, c) - s.without.at(0, 0, c)));
                ov = std::max(ov, std::fabs(s.with.at(x, y, c) - s.without.at(x, y, c)));
            }
            if (bg > 8.0f / 255.0f) data.add(x, y);
            if (ov > 8.0f / 255.0f && x > s.with.width / 3) legend.add(x, y);  // right of the time label
        }
    ASSERT_FALSE(data.empty());
    ASSERT_FALSE(legend.empty());
    EXPECT_GT(legend.x0, data.x1) << "the legend covers the data";
    EXPECT_LT(legend.x0 - data.x1, s.with.width / 8) << "the legend stands far from the data (at the frame's edge?)";
    EXPECT_LT(legend.x1, s.with.width - 1);

    const double n = stat(s.table, "legend_ticks"), first = stat(s.table, "legend_tick_first"),
                 step = stat(s.table, "legend_tick_step"), lo = stat(s.table, "legend_min"), hi = stat(s.table, "legend_max");
    EXPECT_GE(n, 3) << s.table;
    EXPECT_LE(n, 5) << s.table;
    EXPECT_GE(first, lo);
    EXPECT_LE(first + (n - 1) * step, hi);
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
    EXPECT_TRUE(std::fabs(mantissa - 1) < 1e-9 || std::fabs(mantissa - 2) < 1e-9 || std::fabs(mantissa - 2.5) < 1e-9 ||
                std::fabs(mantissa - 5) < 1e-9)
        << "step " << step;
    EXPECT_NEAR(std::remainder(first, step), 0.0, 1e-9 * step) << "ticks on multiples of the step";
}

// Text scales with the output height: legible at 480x270 (the time label at least 9 px tall),
// not huge at 4K (less than 3 % of the height, and less than 4x the 270-line label for 8x the
// lines).
TEST(Framing, TextIsLegibleSmallAndModestAt4K) {
    auto label_height = [](const Shot& s) {
        Box b;
        for (int y = 0; y < s.with.height / 4; ++y)
            for (int x = 0; x < s.with.width / 4; ++x) {
                float d = 0;
                for (int c = 0; c < 3; ++c) d = std::max(d, std::fabs(s.with.at(x, y, c) - s.without.at(x, y, c)));
                if (d > 0.25f) b.add(x, y);
            }
        return b.empty() ? 0 : b.y1 - b.y0 + 1;
    };
    const int small = label_height(shot("text_270", "480x270")), big = label_height(shot("text_2160", "3840x2160"));
    EXPECT_GE(small, 9) << "the time label at 480x270";
    EXPECT_LT(big, 0.03 * 2160) << "the time label at 3840x2160";
    EXPECT_LT(big, 4 * small) << small << " px at 270 lines, " << big << " px at 2160";
}
