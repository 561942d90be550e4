// The line kit's hooks and variant 3 (geometric_fade) on real GL (llvmpipe). Two straight
// pathlets seen square-on: a fast one (4 units/s, y = 0) and a slow one (1 unit/s, y = 4),
// times 0..10 s, so every column of the image maps to a known point of each line and the
// kit's age and arc lengths can be checked against their exact values.
#include "frame_capture.hpp"
#include "golden.hpp"
#include "graph/graph_model.hpp"
#include "graph/hook_params.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

namespace fs = std::filesystem;
using namespace pathlet;

namespace {

const std::string kSrc = PATHLET_SOURCE_DIR;
const std::string kHere = PATHLET_TEST_SOURCE_DIR;
const glm::ivec2 kSize{400, 100};
// The square-on camera of tests/support: x to the right, kPxPerUnit pixels per unit at z = 0.
const float kPxPerUnit = square_on_pixels_per_unit(kSize.y);

Runtime& rt() { return test_runtime({PATHLET_TEST_PLUGIN_DIR}); }

std::string scratch(const std::string& name) { return test_scratch_dir("pathlet_fades") + "/" + name; }

const std::string& camera_file() {
    static const std::string path = write_square_on_camera(scratch("camera.json"));
    return path;
}

const Scene& two_speeds() { return two_speed_lines_scene(); }

float column_x(int col) { return (float(col) + 0.5f - 0.5f * float(kSize.x)) / kPxPerUnit + 5.0f; }

Frame render(const std::string& graph, std::vector<std::string> sets, double t = 10.0) {
    RenderOptions opt;
    opt.graph_path = graph.find('/') == std::string::npos ? kHere + "/graphs/" + graph : graph;
    opt.sets = std::move(sets);
    opt.size = kSize;
    opt.camera_path = camera_file();
    opt.time.start = t;
    return render_frame(rt(), two_speeds(), opt, {"color"});
}

bool covered(const Image& c, int x, int y) { return c.at(x, y, 3) > 0.5f; }

// Covered pixels per column within the band of one line (the fast line is below the centre row).
std::vector<int> widths(const Image& c, bool fast) {
    std::vector<int> w(size_t(c.width), 0);
    for (int y = fast ? c.height / 2 : 0; y < (fast ? c.height : c.height / 2); ++y)
        for (int x = 0; x < c.width; ++x) w[size_t(x)] += covered(c, x, y);
    return w;
}

struct Extent {
    int first = -1, last = -1, max_width = 0;
};
Extent extent(const std::vector<int>& w) {
    Extent e;
    for (int x = 0; x < int(w.size()); ++x)
        if (w[size_t(x)] > 0) {
            if (e.first < 0) e.first = x;
            e.last = x;
            e.max_width = std::max(e.max_width, w[size_t(x)]);
        }
    return e;
}

// Pixels from the tail end (left) to the first column at 90 % of the full width.
int tail_taper_px(const std::vector<int>& w) {
    Extent e = extent(w);
    for (int x = e.first; x <= e.last; ++x)
        if (w[size_t(x)] >= 0.9 * e.max_width) return x - e.first;
    return -1;
}

// The row through the middle of a line's band (its widest coverage) for reading colours.
int centre_row(const Image& c, int col, bool fast) {
    int lo = -1, hi = -1;
    for (int y = fast ? c.height / 2 : 0; y < (fast ? c.height : c.height / 2); ++y)
        if (covered(c, col, y)) {
            if (lo < 0) lo = y;
            hi = y;
        }
    return lo < 0 ? -1 : (lo + hi) / 2;
}

}  // namespace

TEST(LineKit, AgeHookSeesZeroAtTheHeadAndOneAtTheTail) {
    // t = 8, window 4: the fast pathlet spans x = 1..17 (times 4..8).
    Frame f = render("kit_probe.json", {"probe.probe=age", "window=4"}, 8.0);
    const Image& c = f["color"];
    Extent e = extent(widths(c, true));
    ASSERT_GT(e.last - e.first, 60) << "fast pathlet not found";
    EXPECT_NEAR(column_x(e.first), 1.0f, 0.5f);
    EXPECT_NEAR(column_x(e.last), 17.0f, 0.5f);
    int checked = 0;
    for (int col = e.first + 2; col <= e.last - 2; col += 7) {
        int row = centre_row(c, col, true);
        ASSERT_GE(row, 0);
        float t = (column_x(col) + 15.0f) / 4.0f, age = (8.0f - t) / 4.0f;
        EXPECT_NEAR(c.at(col, row, 0), age, 0.03f) << "column " << col << " (x " << column_x(col) << ")";
        ++checked;
    }
    EXPECT_GT(checked, 8);
    EXPECT_LT(c.at(e.last - 1, centre_row(c, e.last - 1, true), 0), 0.05f) << "head";
    EXPECT_GT(c.at(e.first + 1, centre_row(c, e.first + 1, true), 0), 0.95f) << "tail";
}

TEST(LineKit, ArcLengthsRunFromTheHeadAndFromTheTail) {
    // Whole pathlets (t = 10, window 10); the fast one is 40 units long: colour = arc / 40.
    Frame f = render("kit_probe.json", {"probe.probe=arc", "probe.scale=40"});
    const Image& c = f["color"];
    Extent e = extent(widths(c, true));
    ASSERT_GT(e.last - e.first, 100);
    for (int col = e.first + 3; col <= e.last - 3; col += 11) {
        int row = centre_row(c, col, true);
        float from_tail = column_x(col) + 15.0f;
        EXPECT_NEAR(c.at(col, row, 0), (40.0f - from_tail) / 40.0f, 0.03f) << "from head, column " << col;
        EXPECT_NEAR(c.at(col, row, 1), from_tail / 40.0f, 0.03f) << "from tail, column " << col;
    }
}

TEST(LineKit, WidthHookTapersTheQuad) {
    Frame plain = render("kit_probe.json", {"probe.probe=age"});
    Frame taper = render("kit_probe.json", {"probe.probe=taper"});
    std::vector<int> wp = widths(plain["color"], true), wt = widths(taper["color"], true);
    Extent e = extent(wp);
    ASSERT_GT(e.max_width, 5);
    // Width 1 - age: full at the head, half in the middle, a point at the tail.
    auto at = [&](float frac) { return wt[size_t(e.first + int(frac * float(e.last - e.first)))]; };
    EXPECT_GE(at(0.97f), e.max_width - 1);
    EXPECT_NEAR(at(0.5f), 0.5 * e.max_width, 1.5);
    EXPECT_LE(at(0.03f), 1);
    for (float a = 0.1f; a < 0.9f; a += 0.1f) EXPECT_LE(at(a), at(a + 0.1f) + 1) << "monotonic from tail to head";
    for (int x = 0; x < kSize.x; ++x) ASSERT_LE(wt[size_t(x)], wp[size_t(x)]) << "taper outside the quad at " << x;
}

// lines::screen_rect allows for a width hook of at most GpuScene::kMaxWidthHook, so the kit
// clamps the hook there: 10x draws exactly what 4x draws, while 2x and 4x still widen.
TEST(LineKit, WidthHookIsClampedToWhatThePostPassesAllowFor) {
    auto coverage = [](const Image& c) {
        size_t n = 0;
        for (int y = 0; y < c.height; ++y)
            for (int x = 0; x < c.width; ++x) n += covered(c, x, y);
        return double(n);
    };
    auto widened = [&](const char* scale) {
        return render("kit_probe.json", {"probe.probe=widen", std::string("probe.scale=") + scale, "line_width=0.3"});
    };
    const double c1 = coverage(widened("1")["color"]), c2 = coverage(widened("2")["color"]);
    Frame four = widened("4"), ten = widened("10");
    const double c4 = coverage(four["color"]);
    ASSERT_GT(c1, 100.0);
    EXPECT_GT(c2, 1.5 * c1) << c1 << " " << c2;  // pixel rounding: thin lines are not exactly proportional
    EXPECT_GT(c4, 1.5 * c2) << c2 << " " << c4;
    EXPECT_EQ(ten["color"].pixels, four["color"].pixels) << "a hook of 10 must draw as 4";
}

TEST(LineKit, MisspeltUniformIsAnErrorNamingPassProgramAndUniform) {
    try {
        render("kit_probe.json", {"probe.probe=typo"});
        FAIL() << "a uniform the program does not declare must not be ignored";
    } catch (const std::exception& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("pass 'probe'"), std::string::npos) << msg;
        EXPECT_NE(msg.find("kit_probe_color.frag"), std::string::npos) << msg;
        EXPECT_NE(msg.find("'u_sclae'"), std::string::npos) << msg;
        EXPECT_NE(msg.find("did you mean 'u_scale'"), std::string::npos) << msg;
    }
}

TEST(GeometricFade, TailsAreNarrowerThanHeads) {
    Frame f = render("fade_only.json", {"fade.tail_fade=0.5", "fade.head_fade=0.15"});
    for (bool fast : {true, false}) {
        std::vector<int> w = widths(f["color"], fast);
        Extent e = extent(w);
        ASSERT_GT(e.last - e.first, 20);
        int quarter = (e.last - e.first) / 4;
        double tail = 0, head = 0;
        for (int k = 0; k < quarter; ++k) tail += w[size_t(e.first + k)], head += w[size_t(e.last - k)];
        EXPECT_LT(tail, 0.6 * head) << (fast ? "fast" : "slow") << " pathlet";
        EXPECT_LE(w[size_t(e.first)], 2) << "the tail ends in a point";
    }
}

TEST(GeometricFade, NoPixelOutsideTheUntaperedQuad) {
    // The quads are not planar (each end faces the eye), so a narrower quad's two triangles
    // may cross the wider one's diagonal by a fraction of a pixel: a tapered pixel must lie on
    // the full quad or touch it, and almost all must lie on it.
    Frame tapered = render("fade_only.json", {"fade.fade_curve=round"}, 7.0);
    Frame full = render("fade_only.json", {"fade.tail_fade=0", "fade.head_fade=0"}, 7.0);
    const Image &a = tapered["color"], &b = full["color"];
    auto on_full = [&](int x, int y) { return x >= 0 && y >= 0 && x < b.width && y < b.height && covered(b, x, y); };
    size_t n = 0, edge = 0, fewer = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (covered(a, x, y)) {
                ++n;
                if (!on_full(x, y)) {
                    ++edge;
                    ASSERT_TRUE(on_full(x - 1, y) || on_full(x + 1, y) || on_full(x, y - 1) || on_full(x, y + 1))
                        << "tapered pixel away from the full quad at " << x << "," << y;
                }
            }
            fewer += on_full(x, y) && !covered(a, x, y);
        }
    EXPECT_GT(n, 300u);
    EXPECT_LE(edge, n / 200) << edge << " of " << n << " tapered pixels off the full quad";
    EXPECT_GT(fewer, 100u) << "the taper removed too little to be a taper";
}

TEST(GeometricFade, ArcLengthTaperIsTheSameOnScreenForFastAndSlowPathlets) {
    // Fast and slow pathlet, same tail share: in time mode the fast one's taper is 4x longer on
    // screen (the study's complaint); in arc-length mode both taper over the same length.
    auto lengths = [&](const std::string& measure) {
        Frame f = render("fade_only.json", {"fade.tail_fade=0.1", "fade.head_fade=0", "fade.fade_measure=" + measure});
        return std::pair<int, int>(tail_taper_px(widths(f["color"], true)), tail_taper_px(widths(f["color"], false)));
    };
    auto [fast_t, slow_t] = lengths("time");
    auto [fast_a, slow_a] = lengths("arc_length");
    ASSERT_GT(slow_t, 0);
    EXPECT_GT(double(fast_t) / slow_t, 2.5) << "time mode: fast " << fast_t << " px, slow " << slow_t << " px";
    ASSERT_GT(fast_a, 8);
    EXPECT_NEAR(double(fast_a) / slow_a, 1.0, 0.10) << "arc mode: fast " << fast_a << " px, slow " << slow_a << " px";
}

TEST(GeometricFade, Variant3GraphMatchesGoldenAndIsClean) {
    RenderOptions opt;
    opt.graph_path = kSrc + "/graphs/variant3_geomfade.json";
    opt.sets = {"window=3", "line_width=1.2", "overlay=false"};
    opt.size = {160, 120};
    opt.time.start = 6.0;
    Frame f = render_frame(rt(), helix_bundle_scene(), opt, {"final", "color"});
    const Image& img = f["final"];
    EXPECT_FALSE(has_nan(img));
    EXPECT_TRUE(matches_golden(img, kHere + "/goldens/variant3_geomfade.png"));
    // Background untouched: white where the G-buffer has no line, here or in the 4 neighbours
    // (those get the edge anti-aliasing's share of a line).
    const Image& c = f["color"];
    auto line_at = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < c.width && y < c.height && c.at(x, y, 3) >= 0.5f;
    };
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x)
            if (!line_at(x, y) && !line_at(x + 1, y) && !line_at(x - 1, y) && !line_at(x, y + 1) && !line_at(x, y - 1)) {
                ASSERT_GT(img.at(x, y, 0), 0.99f) << x << "," << y;
            }
    Frame again = render_frame(rt(), helix_bundle_scene(), opt, {"final"});
    EXPECT_EQ(again["final"].pixels, img.pixels) << "deterministic";
}

TEST(PluginPath, UnknownTypeNamesTheSearchPathAndDoesNotCascade) {
    std::string file = scratch("unknown_type.json");
    {
        std::ifstream in(kSrc + "/graphs/variant1_lineao.json");
        std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        s.replace(s.find("\"type\": \"gbuffer\""), 17, "\"type\": \"my_fade\"");
        std::ofstream(file) << s;
    }
    Runtime fresh;
    fresh.load_plugins({});
    std::vector<Diagnostic> d = validate_graph(parse_graph_file(file), fresh.registry);
    ASSERT_EQ(d.size(), 1u) << "one cause, one error; got " << d.size() << (d.empty() ? "" : ": " + d[1 % d.size()].str());
    EXPECT_EQ(d[0].pointer, "/passes/0/type");
    EXPECT_NE(d[0].message.find("--plugin-dir"), std::string::npos) << d[0].message;
    EXPECT_NE(d[0].message.find("PATHLET_PLUGIN_PATH"), std::string::npos);
    EXPECT_NE(d[0].message.find("plugin_dirs"), std::string::npos);
    ASSERT_FALSE(fresh.registry.searched_dirs().empty());
    EXPECT_NE(d[0].message.find(fresh.registry.searched_dirs().back()), std::string::npos) << "names where it looked";
}

TEST(PluginPath, GraphListsPluginFoldersRelativeToItself) {
    // A copy of the probe graph beside a link to the fixture's plugin folder.
    fs::path dir = fs::path(scratch("graph_dirs")), link = dir / "my_plugins";
    fs::create_directories(dir);
    fs::remove(link);
    fs::create_directory_symlink(PATHLET_TEST_PLUGIN_DIR, link);
    std::string file = (dir / "probe.json").string();
    {
        std::ifstream in(kHere + "/graphs/kit_probe.json");
        std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        s.replace(s.find("\"version\": 1,"), 13, "\"version\": 1, \"plugin_dirs\": [\"my_plugins\"],");
        std::ofstream(file) << s;
    }
    Runtime fresh;
    fresh.load_plugins({});
    GraphFile g = parse_graph_file(file);
    ASSERT_EQ(g.plugin_dirs.size(), 1u);
    EXPECT_EQ(g.plugin_dirs[0], link.string());
    EXPECT_FALSE(validate_graph(g, fresh.registry).empty()) << "kit_probe is not on the default path";
    // The folder is not trusted (a graph file may name any folder): nothing is loaded.
    EXPECT_THROW(fresh.load_graph_plugins(g), GraphError);
    EXPECT_EQ(fresh.registry.find("kit_probe"), nullptr);
    fresh.trust_graph_plugins = true;  // --trust-graph-plugins
    fresh.load_graph_plugins(g);
    EXPECT_TRUE(validate_graph(g, fresh.registry).empty());
}

TEST(PassDocs, ReadmeTablesMatchTheDeclarations) {
    // Every built-in pass README embeds its parameter and pin tables generated from the one
    // declaration (scripts/update-pass-docs.sh), so docs cannot drift from the code.
    size_t checked = 0;
    for (const auto& e : fs::directory_iterator(kSrc + "/passes")) {
        if (!fs::is_directory(e.path())) continue;
        const std::string type = e.path().filename().string();
        const PassTypeInfo* t = rt().registry.find(type);
        if (!t) continue;
        std::ifstream in(e.path() / "README.md");
        ASSERT_TRUE(in) << type << " has no README.md";
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::string begin = "<!-- pathlet passes --describe " + type + " --markdown -->\n\n";
        const std::string end = "\n<!-- end of generated tables -->";
        size_t a = text.find(begin), b = text.find(end);
        ASSERT_NE(a, std::string::npos) << type << "/README.md lacks the generated tables; run scripts/update-pass-docs.sh";
        ASSERT_NE(b, std::string::npos) << type << "/README.md";
        // As `passes --describe` shows it: with the parameters of its default hooks.
        EXPECT_EQ(text.substr(a + begin.size(), b - a - begin.size()), instance_type_with(*t)->markdown())
            << type << "/README.md is out of date: run scripts/update-pass-docs.sh";
        EXPECT_EQ(text.find("shared/"), std::string::npos) << type << "/README.md must be self-contained";
        ++checked;
    }
    EXPECT_GE(checked, 10u);
    // The index in passes/README.md: every built-in pass, one row each.
    std::vector<const PassTypeInfo*> builtin;
    for (const PassTypeInfo* t : rt().registry.all())
        if (fs::is_directory(kSrc + "/passes/" + t->type)) builtin.push_back(t);
    std::ifstream in(kSrc + "/passes/README.md");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string begin = "<!-- pathlet passes --markdown -->\n\n", end = "\n<!-- end of generated tables -->";
    const size_t a = text.find(begin), b = text.find(end);
    ASSERT_NE(a, std::string::npos) << "passes/README.md lacks the index; run scripts/update-pass-docs.sh";
    EXPECT_EQ(text.substr(a + begin.size(), b - a - begin.size()), index_markdown(builtin))
        << "passes/README.md is out of date: run scripts/update-pass-docs.sh";
    EXPECT_EQ(builtin.size(), checked);
}

// ---- aorta_backface: the wall as context behind the lines ---------------------------------

namespace {
// The helix bundle inside a closed tube (radius 5 around the x axis, x = -2..42), outward
// normals, like a vessel wall around its pathlines.
const Scene& bundle_in_a_tube() {
    static const Scene scene = [] {
        Scene s = helix_bundle_scene();
        Mesh m;
        const int ring = 32, rows = 12;
        for (int r = 0; r <= rows; ++r)
            for (int k = 0; k < ring; ++k) {
                float a = 6.2831853f * float(k) / float(ring), x = -2.0f + 44.0f * float(r) / float(rows);
                m.position.push_back({x, 5.0f * std::cos(a), 5.0f * std::sin(a)});
                m.normal.push_back({0.0f, std::cos(a), std::sin(a)});
            }
        for (int r = 0; r < rows; ++r)
            for (int k = 0; k < ring; ++k) {
                uint32_t a = uint32_t(r * ring + k), b = uint32_t(r * ring + (k + 1) % ring), c = a + uint32_t(ring),
                         d = b + uint32_t(ring);
                m.index.insert(m.index.end(), {a, b, d, a, d, c});
            }
        s.mesh = m;
        s.source = "helix bundle in a tube (test_fades)";
        return s;
    }();
    return scene;
}

Frame render_v1(const Scene& scene, std::vector<std::string> sets) {
    RenderOptions opt;
    opt.graph_path = kSrc + "/graphs/variant1_lineao.json";
    sets.insert(sets.begin(), {"window=3", "line_width=1.2"});
    opt.sets = sets;
    opt.size = {160, 120};
    opt.time.start = 6.0;
    return render_frame(rt(), scene, opt, {"final", "smooth", "composed", "lit"});
}
}  // namespace

TEST(AortaBackface, WallOffOrNoWallIsTodaysImageBitForBit) {
    // "lit" is the image the graph ended with before the wall pass existed.
    Frame none = render_v1(helix_bundle_scene(), {});
    Frame off = render_v1(bundle_in_a_tube(), {"wall=false"});
    EXPECT_EQ(off["composed"].pixels, off["lit"].pixels) << "wall=false passes the image through";
    EXPECT_EQ(none["composed"].pixels, none["lit"].pixels) << "without a mesh the pass only copies";
    // (passes/lineao/tests's variant-1 golden, rendered through this graph, guards the unchanged look.)
}

TEST(Overlay, OverlayOffIsTheImageBeforeItBitForBit) {
    Frame off = render_v1(bundle_in_a_tube(), {"overlay=false"});
    Frame on = render_v1(bundle_in_a_tube(), {});
    EXPECT_EQ(off["final"].pixels, off["smooth"].pixels) << "overlay=false passes the image through";
    EXPECT_EQ(on["smooth"].pixels, off["smooth"].pixels) << "the overlay must not change what comes before it";
    EXPECT_NE(on["final"].pixels, on["smooth"].pixels) << "overlay=true draws the time and the legend";
}

TEST(EdgeAA, AaOffIsTheComposedImageMadeOpaque) {
    Frame off = render_v1(bundle_in_a_tube(), {"aa=false"});
    const Image &s = off["smooth"], &c = off["composed"];
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            for (int k = 0; k < 3; ++k) ASSERT_EQ(s.at(x, y, k), c.at(x, y, k)) << x << "," << y;
            ASSERT_EQ(s.at(x, y, 3), 1.0f) << "alpha = opaque flattens onto the background";
        }
    Frame on = render_v1(bundle_in_a_tube(), {});
    EXPECT_NE(on["smooth"].pixels, off["smooth"].pixels) << "aa=true changes the edges";
}

TEST(AortaBackface, WallShowsBehindTheLinesAndNeverChangesThem) {
    Frame on = render_v1(bundle_in_a_tube(), {});
    Frame off = render_v1(bundle_in_a_tube(), {"wall=false"});
    const Image &a = on["composed"], &b = off["composed"], &lit = on["lit"];
    EXPECT_EQ(lit.pixels, off["lit"].pixels) << "the wall must not touch LineAO or the lines";
    size_t wall = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const bool line = lit.at(x, y, 3) > 0.5f;
            for (int c = 0; c < 4; ++c)
                if (line) {
                    ASSERT_EQ(a.at(x, y, c), b.at(x, y, c)) << "a line pixel changed at " << x << "," << y;
                }
            if (!line && a.at(x, y, 3) == 1.0f && b.at(x, y, 3) == 0.0f) ++wall;
        }
    EXPECT_GT(wall, 500u) << "the wall should show around and between the lines";
    EXPECT_TRUE(matches_golden(a, kHere + "/goldens/variant1_wall.png"));
}

TEST(AortaBackface, UnderOitTheWallShowsWhereTheImageIsClearAndNeverOverALine) {
    // variant2_oit's depth is its opaque G-buffer's, which also holds fragments too faint to
    // reach a list (rims, faded tips): with clear_shows_wall the wall shows there too, as
    // around the lines; without it those pixels stay background, holes in the wall.
    auto v2 = [](std::vector<std::string> sets) {
        RenderOptions opt;
        opt.graph_path = kSrc + "/graphs/variant2_oit.json";
        // Smooth ramps over whole pathlets: their tails stay below 1/510 opacity for a few pixels.
        sets.insert(sets.begin(), {"window=3", "line_width=1.2", "overlay=false", "tail_fade=1", "head_fade=0",
                                   "fill_list.fade_curve=smooth"});
        opt.sets = sets;
        opt.size = {160, 120};
        opt.time.start = 6.0;
        return render_frame(rt(), bundle_in_a_tube(), opt, {"composed", "lit", "depth"});
    };
    Frame on = v2({});
    Frame off = v2({"wall=false"});
    Frame holes = v2({"wall.clear_shows_wall=false"});
    const Image &a = on["composed"], &b = off["composed"], &h = holes["composed"], &lit = on["lit"];
    EXPECT_EQ(lit.pixels, off["lit"].pixels) << "the wall must not touch the lines";
    size_t wall = 0, faint = 0, faint_walled = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const bool line = lit.at(x, y, 3) > 0.0f;
            for (int c = 0; c < 4; ++c)
                if (line) {
                    ASSERT_EQ(a.at(x, y, c), b.at(x, y, c)) << "a line pixel changed at " << x << "," << y;
                }
            if (line) continue;
            wall += a.at(x, y, 3) == 1.0f;
            if (on["depth"].at(x, y, 0) < 1.0f) {  // a fragment the image does not show
                ++faint;
                faint_walled += a.at(x, y, 3) == 1.0f && h.at(x, y, 3) == 0.0f;
            }
        }
    EXPECT_GT(wall, 500u) << "the wall should show around and between the lines";
    EXPECT_GT(faint, 5u) << "the bundle's rims and tips leave clear pixels with a depth";
    EXPECT_GT(faint_walled, faint / 2) << "the wall must show at clear pixels the depth alone would hide";
}
