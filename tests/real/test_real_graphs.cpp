// Real-data conformance: every shipped graph that draws lines, on every real data set in
// ../shared/data/real (none of it made by this project), at the default framing and the
// graph's defaults, checked for what a person would see:
//   - the lines cover a sane share of the frame (overlay and wall off),
//   - the median line width on screen at the default framing and size (1280x720) is a few
//     pixels: tubes, outlines and AO read, and no fat ribbons,
//   - variant 3 never covers more of the frame than variant 1 at the same window,
//   - no NaN in the picture or in the float G-buffer and AO maps,
//   - the wall shows where the data set has one,
//   - the legend's range lies within the data's speeds.
// The data sets are prepared as a user would: the aneurysm's text rows as they are, the
// 4DFlowNet aorta and the carotid field traced with `pathlet trace`'s defaults (the carotid's
// vessel from VTK's own threshold, 175) with marching-cubes walls, the vmtk centrelines as
// streamlines inside the vmtk surface, the fornix tracts from TrackVis. Small frames, one each:
// seconds in CI. Skipped, saying so, where ../shared/data/real is absent.
#include "frame_capture.hpp"
#include "image_probes.hpp"
#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
#include "shipped_graphs.hpp"
#include "trace/field_readers.hpp"
#include "trace/marching_cubes.hpp"
#include "trace/tracer.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>

using namespace pathlet;

namespace {

std::string real_dir() {
    const char* env = std::getenv("PATHLET_REAL_DATA_DIR");
    return env && *env ? env : "";
}

// What a user runs: `pathlet trace FIELD -o OUT --wall WALL` with its defaults.
Scene traced(const std::string& field_path, float mask_threshold) {
    trace::VelocityField field = trace::load_velocity_field(field_path);
    if (mask_threshold > 0) field.mask_from_scalars(mask_threshold);
    trace::TraceOptions o;
    o.time_end = 10.0f;  // --duration's default
    o.threads = 2;
    Scene s;
    s.lines = trace::trace_pathlines(field, o);
    s.mesh = trace::vessel_wall(field);
    s.source = field_path;
    return s;
}

struct RealSet {
    Scene scene;
    std::string missing;  // why it is skipped
};

const std::vector<std::string> kSets = {"aneurysm", "arch", "carotid", "vmtk", "fornix"};

const RealSet& real_set(const std::string& name) {
    static std::map<std::string, RealSet> cache;
    auto it = cache.find(name);
    if (it != cache.end()) return it->second;
    RealSet& r = cache[name];
    const std::string d = real_dir();
    const std::map<std::string, std::string> file = {
        {"aneurysm", "aneurysm-pathlines/blood_flow"},
        {"arch", "aortic-arch-cfd-4dflownet/example_data_HR.h5"},
        {"carotid", "carotid-vtk/carotid.vtk"},
        {"vmtk", "vmtk-abdominal-aorta/aorta-centerline.vtp"},
        {"fornix", "fornix-tractography/tracks300.trk"}};
    const std::string path = d + "/" + file.at(name);
    if (d.empty() || !std::filesystem::exists(path)) {
        r.missing = "real data absent: " + (d.empty() ? std::string("PATHLET_REAL_DATA_DIR unset") : path) +
                    " (../shared/data/real beside the checkout)";
        return r;
    }
    if (name == "arch") r.scene = traced(path, 0);
    else if (name == "carotid") r.scene = traced(path, 175.0f);
    else {
        io::LoadOptions o;
        o.streamlines = name == "vmtk";
        r.scene.lines = io::load_pathlines(path, o);
        r.scene.source = path;
        if (name == "vmtk") r.scene.mesh = io::load_mesh(d + "/vmtk-abdominal-aorta/aorta-surface.stl");
    }
    return r;
}

// Share of pixels differing from the white background by more than 8 levels.
double coverage(const Image& im) {
    size_t n = 0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            float d = 0;
            for (int c = 0; c < 3; ++c) d = std::max(d, std::fabs(1.0f - im.at(x, y, c)));
            n += d > 8.0f / 255.0f;
        }
    return double(n) / double(std::max(im.width * im.height, 1));
}

double changed_share(const Image& a, const Image& b) {
    size_t n = 0;
    for (size_t i = 0; i + 3 < a.pixels.size(); i += size_t(a.channels)) {
        float d = 0;
        for (int c = 0; c < 3; ++c) d = std::max(d, std::fabs(a.pixels[i + size_t(c)] - b.pixels[i + size_t(c)]));
        n += d > 8.0f / 255.0f;
    }
    return double(n) / double(std::max<size_t>(a.pixels.size() / size_t(a.channels), 1));
}

// Median width in pixels of the lines visible at time t (all of them when drawn whole), at the
// default framing of a 1280x720 frame, for a line `width` world units wide.
double median_width_px(const Scene& s, double t, double window, float width) {
    const glm::ivec2 size(1280, 720);
    const Camera cam = frame_bounds(s.bounds(), size);
    const bool whole = s.lines.timeless || window <= 0;
    std::vector<double> px;
    for (size_t i = 0; i < s.lines.point_count(); ++i) {
        if (!whole && (s.lines.time[i] < t - window || s.lines.time[i] > t)) continue;
        const glm::vec4 e = cam.view * glm::vec4(s.lines.position[i], 1.0f);
        if (-e.z <= 0) continue;
        px.push_back(double(width) * 0.5 * size.y * cam.proj[1][1] / -e.z);
    }
    if (px.empty()) return 0;
    std::nth_element(px.begin(), px.begin() + long(px.size() / 2), px.end());
    return px[px.size() / 2];
}

double mid_time(const Scene& s) {
    return s.lines.timeless ? 0.0 : 0.5 * (double(s.lines.time_min()) + double(s.lines.time_max()));
}

// One frame of `g` with overlay and wall as given (where the graph has them) plus `extra`.
Frame render(const ShippedGraph& g, const Scene& scene, bool wall, std::vector<std::string> extra,
             const std::vector<std::string>& names) {
    RenderOptions opt;
    opt.graph_path = g.path;
    opt.size = {320, 180};
    opt.time.start = mid_time(scene);
    if (g.has_variable("overlay")) opt.sets.push_back("overlay=false");
    if (g.has_variable("wall")) opt.sets.push_back(std::string("wall=") + (wall ? "true" : "false"));
    opt.sets.insert(opt.sets.end(), extra.begin(), extra.end());
    return render_frame(test_runtime(), scene, opt, names);
}

std::string picture(const ShippedGraph& g) {  // the last 8-bit output: what is shown
    std::string name;
    for (const auto& o : g.file.outputs)
        for (const auto& r : g.file.resources)
            if (r.name == o.resource && r.format == "rgba8") name = o.resource;
    return name;
}

// Every check on one graph and data set; the numbers go to the test's XML properties.
void expect_what_a_person_sees(const std::string& set, const Scene& scene, const ShippedGraph& g) {
    test_runtime();  // the GL context unsupported_here asks
    if (const std::string why = g.unsupported_here(); !why.empty()) {
        std::printf("skipped: %s\n", why.c_str());
        return;
    }
    const std::string what = set + " through " + g.name;
    auto record = [&](const std::string& key, double v) { ::testing::Test::RecordProperty(g.name + "_" + key, std::to_string(v)); };
    const std::string shown = picture(g);
    ASSERT_FALSE(shown.empty()) << what;
    std::vector<std::string> names{shown};
    for (const char* f : {"normal_depth", "ao"})  // float maps that would carry a NaN on
        for (const auto& r : g.file.resources)
            if (r.name == f) names.push_back(f);

    const Frame f = render(g, scene, false, {}, names);
    for (const auto& n : names) EXPECT_FALSE(has_nan(f[n])) << what << ": " << n;

    // Coverage of the lines alone.
    const double cov = coverage(f[shown]);
    record("coverage_percent", 100 * cov);
    EXPECT_GT(cov, 0.002) << what << ": the lines cover " << 100 * cov << " % of the frame";
    EXPECT_LT(cov, 0.40) << what << ": the lines cover " << 100 * cov << " % of the frame";

    // Line width on screen at the default framing and size.
    ASSERT_TRUE(f.stats.count("line_width")) << what << ": the line pass reports its width";
    const std::string wdef = g.variable_default("window");
    const double window = wdef.empty() ? 1.0 : std::stod(wdef);
    const double px = median_width_px(scene, mid_time(scene), window, float(f.stats.at("line_width")));
    record("median_width_px_720p", px);
    EXPECT_GE(px, 2.0) << what << ": lines " << px << " px wide at 1280x720";
    EXPECT_LE(px, 8.0) << what << ": lines " << px << " px wide at 1280x720";

    // The wall, where the data set has one.
    if (scene.mesh && g.has_variable("wall")) {
        const double wall = changed_share(render(g, scene, true, {}, {shown})[shown], f[shown]);
        record("wall_percent", 100 * wall);
        EXPECT_GT(wall, 0.005) << what << ": the wall changes " << 100 * wall << " % of the frame";
    }

    // The legend's range (the overlay reports it even when hidden) within the data's speeds.
    if (g.has_pass("overlay") && !scene.lines.timeless && g.variable_default("colormap") != "\"direction\"") {
        ASSERT_TRUE(f.stats.count("legend_min") && f.stats.count("legend_max")) << what;
        const double lo = f.stats.at("legend_min"), hi = f.stats.at("legend_max");
        EXPECT_LT(lo, hi) << what;
        EXPECT_GE(lo, double(scene.lines.speed_min()) * (1 - 1e-6)) << what << ": legend from " << lo;
        EXPECT_LE(hi, double(scene.lines.speed_max()) * (1 + 1e-6)) << what << ": legend to " << hi;
    }

    // Variant 3 (tapered, wider) against variant 1 at variant 3's window.
    if (g.name == "variant3_geomfade") {
        const Frame v1 = render(shipped_graph("variant1_lineao"), scene, false, {"window=" + wdef}, {"final"});
        const double cov1 = coverage(v1["final"]);
        record("variant1_coverage_percent", 100 * cov1);
        EXPECT_LE(cov, cov1) << set << ": variant 3 covers " << 100 * cov << " % of the frame, variant 1 " << 100 * cov1
                             << " % at the same window (" << wdef << " s)";
    }
}

// A test per data set, every line-drawing graph in it: GL, plugins and the data are set up
// once (a process per pair cost 45 x ~5 s on the 2-core CI machine; this is ~3 s each).
struct RealData : ::testing::TestWithParam<std::string> {};

TEST_P(RealData, EveryGraphShowsWhatAPersonExpects) {
    const RealSet& set = real_set(GetParam());
    if (!set.missing.empty()) GTEST_SKIP() << set.missing;
    ASSERT_GT(set.scene.lines.line_count(), 0u);
    for (const auto& name : shipped_graph_names(/*only_drawing_lines=*/true))
        expect_what_a_person_sees(GetParam(), set.scene, shipped_graph(name));
}

INSTANTIATE_TEST_SUITE_P(Real, RealData, ::testing::ValuesIn(kSets),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

}  // namespace
