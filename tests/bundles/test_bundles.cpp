// Tracts as users have them: a bundle per file. Eight bundles cut from the real fornix
// tractography (../shared/data/real; skipped, saying so, where it is absent) given as eight
// files, as a folder and as a glob load as one scene in name order; the default graph follows
// the data; colormap=bundle gives each bundle its palette colour (unlit and under LineAO) and the
// legend names them, whatever the order of the arguments. Bad choices of files are errors that
// name them (exit 2, nothing written).
#include "cli_run.hpp"
#include "common/scene_source.hpp"
#include "frame_capture.hpp"
#include "golden.hpp"
#include "io/pathline_io.hpp"
#include "io/tract_formats.hpp"
#include <pathlet/text.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <regex>
#include <sstream>

using namespace pathlet;

namespace {

const std::string kSrc = PATHLET_SOURCE_DIR;
const std::string kHere = PATHLET_TEST_SOURCE_DIR;

std::string fornix_file() {
    const char* env = std::getenv("PATHLET_REAL_DATA_DIR");
    const std::string path = std::string(env && *env ? env : "") + "/fornix-tractography/tracks300.trk";
    return env && *env && fs::exists(path) ? path : "";
}
#define SKIP_WITHOUT_FORNIX()                                                                                        \
    if (fornix_file().empty())                                                                                       \
    GTEST_SKIP() << "real data absent: fornix-tractography/tracks300.trk under PATHLET_REAL_DATA_DIR "               \
                    "(../shared/data/real beside the checkout)"

std::string scratch(const std::string& name) {
    const std::string d = test_scratch_dir("pathlet_bundles") + "/" + name;
    fs::create_directories(d);
    return d;
}

// The bundles' names, written in an order that is not their sorted one.
const std::vector<std::string> kNames = {"fx_right_body", "fx_left_body",   "fx_right_crus", "fx_left_crus",
                                         "fx_right_col",  "fx_left_col",    "fx_right_fimb", "fx_left_fimb"};

std::vector<std::string> sorted_names() {
    std::vector<std::string> s = kNames;
    std::sort(s.begin(), s.end());
    return s;
}

Pathlines lines_of(const Pathlines& from, const std::vector<size_t>& which) {
    Pathlines out;
    for (size_t li : which) {
        const LineRange r = from.lines[li];
        out.lines.push_back({uint32_t(out.position.size()), r.count});
        out.position.insert(out.position.end(), from.position.begin() + r.first, from.position.begin() + r.first + r.count);
    }
    out.time.assign(out.position.size(), 0.0f);
    out.velocity.assign(out.position.size(), glm::vec3(0.0f));
    return out;
}

// The 300 fornix streamlines cut into 8 spatial bundles (halves by the centroid's x, then
// quarters of each by its y), written as MRtrix .tck files named kNames[k] into a folder of
// their own. Returns the folder; `cut[k]` are bundle k's lines in file order.
struct Cut {
    std::string dir;
    std::vector<Pathlines> bundles;  // in kNames order
};
const Cut& fornix_cut() {
    static const Cut cut = [] {
        Cut c;
        c.dir = scratch("fornix8");
        const Pathlines all = io::load_pathlines(fornix_file());
        std::vector<glm::vec3> centroid(all.line_count());
        for (size_t li = 0; li < all.line_count(); ++li) {
            const LineRange r = all.lines[li];
            for (uint32_t k = 0; k < r.count; ++k) centroid[li] += all.position[r.first + k] / float(r.count);
        }
        std::vector<size_t> order(all.line_count());
        std::iota(order.begin(), order.end(), 0);
        std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return centroid[a].x < centroid[b].x; });
        for (int half = 0; half < 2; ++half) {
            const size_t n = order.size() / 2;
            std::vector<size_t> side(order.begin() + long(half * n), order.begin() + long((half + 1) * n));
            std::sort(side.begin(), side.end(), [&](size_t a, size_t b) { return centroid[a].y < centroid[b].y; });
            for (int q = 0; q < 4; ++q) {
                std::vector<size_t> part(side.begin() + long(q * side.size() / 4), side.begin() + long((q + 1) * side.size() / 4));
                std::sort(part.begin(), part.end());
                c.bundles.push_back(lines_of(all, part));
            }
        }
        for (size_t k = 0; k < kNames.size(); ++k) {
            std::ofstream(c.dir + "/" + kNames[k] + ".tck", std::ios::binary) << io::write_tck(c.bundles[k]);
        }
        std::ofstream(c.dir + "/README.md") << "not a data file: a folder's other files are left alone\n";
        return c;
    }();
    return cut;
}

std::vector<std::string> cut_files(bool reversed) {
    std::vector<std::string> f;
    for (const auto& n : kNames) f.push_back(fornix_cut().dir + "/" + n + ".tck");
    if (reversed) std::reverse(f.begin(), f.end());
    return f;
}

Scene load(std::vector<std::string> data) {
    SceneSource s;
    s.data = std::move(data);
    return load_scene(s, true);
}

// The scene holds bundle k = the k-th name in sorted order, its lines as the cut wrote them.
void expect_sorted_bundles(const Scene& s) {
    const Cut& cut = fornix_cut();
    ASSERT_EQ(s.lines.bundle_names, sorted_names());
    ASSERT_EQ(s.lines.line_count(), 300u);
    ASSERT_EQ(s.lines.line_bundle.size(), s.lines.line_count());
    EXPECT_TRUE(s.lines.timeless);
    size_t line = 0;
    for (uint32_t b = 0; b < s.lines.bundle_names.size(); ++b) {
        const size_t k = size_t(std::find(kNames.begin(), kNames.end(), s.lines.bundle_names[b]) - kNames.begin());
        const Pathlines& want = cut.bundles[k];
        for (size_t j = 0; j < want.line_count(); ++j, ++line) {
            ASSERT_EQ(s.lines.line_bundle[line], b) << "line " << line;
            const LineRange got = s.lines.lines[line], w = want.lines[j];
            ASSERT_EQ(got.count, w.count) << s.lines.bundle_names[b] << " line " << j;
            for (uint32_t p = 0; p < w.count; p += 7)
                ASSERT_LT(glm::length(s.lines.position[got.first + p] - want.position[w.first + p]), 1e-3f);
        }
    }
}

// The palette as colormap.glsl declares it (BUNDLE_PALETTE): read from the shader, said once.
std::vector<glm::vec3> bundle_palette() {
    std::ifstream in(kSrc + "/shaders/colormap.glsl");
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    const size_t at = text.find("BUNDLE_PALETTE[BUNDLE_PALETTE_SIZE] =");
    const std::string body = text.substr(at, text.find(";", at) - at);
    std::vector<glm::vec3> p;
    const std::regex v(R"(vec3\(([0-9.]+), ([0-9.]+), ([0-9.]+)\))");
    for (auto it = std::sregex_iterator(body.begin(), body.end(), v); it != std::sregex_iterator(); ++it)
        p.emplace_back(std::stof((*it)[1]), std::stof((*it)[2]), std::stof((*it)[3]));
    return p;
}

Frame render(const Scene& s, const std::string& graph, std::vector<std::string> sets, glm::ivec2 size,
             const std::vector<std::string>& names) {
    RenderOptions opt;
    opt.graph_path = kSrc + "/graphs/" + graph + ".json";
    opt.sets = std::move(sets);
    opt.size = size;
    return render_frame(test_runtime(), s, opt, names);
}

}  // namespace

TEST(Bundles, EightFilesAFolderAndAGlobLoadAsOneSceneOfBundlesInNameOrder) {
    SKIP_WITHOUT_FORNIX();
    const Scene files = load(cut_files(false));
    expect_sorted_bundles(files);
    const Scene reversed = load(cut_files(true));
    EXPECT_EQ(reversed.lines.position, files.lines.position);  // the arguments' order changes nothing
    EXPECT_EQ(reversed.lines.line_bundle, files.lines.line_bundle);
    const Scene folder = load({fornix_cut().dir});
    expect_sorted_bundles(folder);
    const Scene glob = load({fornix_cut().dir + "/fx_*.tck"});
    expect_sorted_bundles(glob);
    EXPECT_EQ(folder.lines.position, files.lines.position);
    EXPECT_EQ(glob.lines.position, files.lines.position);
    // One pseudo-time speed for all: a tenth of the joined data's diagonal per second.
    const Bounds b = files.lines.bounds();
    EXPECT_NEAR(files.lines.speed_max(), 0.1f * glm::length(b.hi - b.lo), 1e-3f * glm::length(b.hi - b.lo));
    EXPECT_NEAR(files.lines.speed_min(), files.lines.speed_max(), 1e-3f * files.lines.speed_max());
}

TEST(Bundles, TheDefaultGraphFollowsTheData) {
    SKIP_WITHOUT_FORNIX();
    SceneSource s;
    s.data = {fornix_cut().dir};
    EXPECT_EQ(default_graph(s), "tracts_lineao");
    s.data = {kSrc + "/tests/engine/data/two_lines.vtk"};
    EXPECT_EQ(default_graph(s), "variant1_lineao");
    s.data = {};
    EXPECT_EQ(default_graph(s), "variant1_lineao");
    // The command says which graph it chose, and draws it.
    const std::string out = scratch("default_graph_out");
    CliRun r = pathlet_cli("render --data " + fornix_cut().dir + " --size 160x90 --out " + out);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("graph: tracts_lineao (the data are tracts"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("bundles: " + text::join(sorted_names())), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(out + "/tracts_lineao/00000.png"));
    r = pathlet_cli("render --data " + kSrc + "/tests/engine/data/two_lines.vtk --time 0 --size 160x90 --no-images");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err.find("graph: "), std::string::npos) << r.err;
}

TEST(Bundles, BadChoicesOfFilesAreErrorsNamingThemAndNothingIsWritten) {
    // Synthetic tracts: two short lines a file.
    Pathlines two;
    two.position = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 1}};
    two.lines = {{0, 3}, {3, 3}};
    const std::string d = scratch("bad_choices"), a = d + "/a", b = d + "/b", empty = d + "/empty";
    fs::create_directories(a), fs::create_directories(b), fs::create_directories(empty);
    std::ofstream(empty + "/notes.md") << "no data here\n";
    std::ofstream(a + "/cst.tck", std::ios::binary) << io::write_tck(two);
    std::ofstream(b + "/cst.tck", std::ios::binary) << io::write_tck(two);
    const std::string timed = kSrc + "/tests/engine/data/two_lines.vtk";
    const std::string out = d + "/out";
    struct Case {
        std::string data, says;
        std::vector<std::string> names;
    };
    const std::vector<Case> cases = {
        {empty, "a folder with no data files", {empty}},
        {"'" + a + "/*.trk'", "the pattern matches no file", {a + "/*.trk"}},
        {a + "/cst.tck " + b + "/cst.tck", "two data files named 'cst'", {a + "/cst.tck", b + "/cst.tck"}},
        {a + "/cst.tck " + timed, "files of mixed kinds", {a + "/cst.tck", timed}},
        {a + "/cst.tck tracts_lineao", "looks like a graph: --data takes every argument", {"tracts_lineao"}},
    };
    for (const Case& c : cases)
        for (const std::string graph : {"", "isl "}) {  // chosen by the data, or given
            SCOPED_TRACE(graph + c.data);
            const CliRun r = pathlet_cli("render " + graph + "--data " + c.data + " --size 64x36 --out " + out);
            EXPECT_EQ(r.code, 2) << r.err;
            EXPECT_EQ(r.err.rfind("\nerror: ") + 1, r.err.find("error: ")) << "one error, the last line:\n" << r.err;
            EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
            for (const auto& n : c.names) EXPECT_NE(r.err.find(n), std::string::npos) << n << "\n" << r.err;
            EXPECT_FALSE(fs::exists(out)) << "a failed render left " << out;
        }
}

TEST(Bundles, EachBundleDrawsInItsPaletteColour) {
    SKIP_WITHOUT_FORNIX();
    const Scene s = load({fornix_cut().dir});
    const std::vector<glm::vec3> palette = bundle_palette();
    ASSERT_EQ(palette.size(), 10u) << "BUNDLE_PALETTE in shaders/colormap.glsl";
    const glm::ivec2 size(320, 180);
    // Unlit: the G-buffer's colour is the palette's entry, exactly (halo off).
    const Frame g = render(s, "gbuffer_only", {"gbuffer.colormap=bundle", "halo=0"}, size, {"color", "line_id"});
    std::vector<size_t> pixels(8, 0);
    size_t wrong = 0;
    for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x) {
            const int id = int(g["line_id"].at(x, y, 0));
            if (id < 0) continue;
            const uint32_t b = s.lines.bundle_of(size_t(id));
            ++pixels[b];
            for (int c = 0; c < 3; ++c) wrong += std::fabs(g["color"].at(x, y, c) - palette[b][c]) > 1.0f / 255.0f;
        }
    EXPECT_EQ(wrong, 0u);
    for (size_t b = 0; b < 8; ++b) EXPECT_GT(pixels[b], 50u) << s.lines.bundle_names[b] << " is not on screen";
    // Lit with LineAO (tracts_lineao, hard edges, no overlay): each bundle's pixels are its
    // palette colour darkened, the same hue: the nearest palette hue is its own.
    const Frame lit = render(s, "tracts_lineao", {"colormap=bundle", "aa=false", "overlay=false", "gbuffer.halo=0"}, size, {"final"});
    size_t lit_pixels = 0, other_hue = 0;
    auto hue_distance = [](glm::vec3 px, glm::vec3 q) {
        const float k = glm::dot(px, q) / glm::dot(q, q);  // px ~ k q under a grey light
        return glm::length(px - k * q);
    };
    for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x) {
            const int id = int(g["line_id"].at(x, y, 0));
            if (id < 0) continue;
            const glm::vec3 px(lit["final"].at(x, y, 0), lit["final"].at(x, y, 1), lit["final"].at(x, y, 2));
            if (glm::length(px) < 0.15f) continue;  // too dark to tell a hue
            ++lit_pixels;
            const uint32_t b = s.lines.bundle_of(size_t(id));
            const float own = hue_distance(px, palette[b]);
            for (size_t o = 0; o < 8; ++o)
                if (o != b && hue_distance(px, palette[o]) < own) {
                    ++other_hue;
                    break;
                }
        }
    EXPECT_GT(lit_pixels, 2000u);
    EXPECT_LT(double(other_hue), 0.01 * double(lit_pixels)) << other_hue << " of " << lit_pixels;
}

TEST(Bundles, TheLegendNamesTheBundlesWhateverTheArgumentsOrder) {
    SKIP_WITHOUT_FORNIX();
    const glm::ivec2 size(480, 270);
    const Frame a = render(load(cut_files(false)), "tracts_lineao", {"colormap=bundle"}, size, {"final"});
    const Frame b = render(load(cut_files(true)), "tracts_lineao", {"colormap=bundle"}, size, {"final"});
    EXPECT_EQ(a.stats.at("legend_bundles"), 8.0);
    EXPECT_EQ(a["final"].pixels, b["final"].pixels);
    EXPECT_TRUE(matches_golden(a["final"], kHere + "/goldens/fornix8_bundles.png"));
    // Direction colours stay the default: the same scene without the set draws no bundle legend.
    const Frame d = render(load(cut_files(false)), "tracts_lineao", {}, size, {"final"});
    EXPECT_EQ(d.stats.count("legend_bundles"), 0u);
    EXPECT_TRUE(matches_golden(d["final"], kHere + "/goldens/fornix8_direction.png"));
}
