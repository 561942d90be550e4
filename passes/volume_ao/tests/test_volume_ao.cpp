// Object-space line AO on tiny synthetic scenes, real GL (llvmpipe): line_density's
// volume and volume_ao's estimate against the ray-traced reference of `pathlet quality`, the
// per-fragment estimate under OIT against the per-pixel one, bad parameters, the memory cap.
#include "executor.hpp"
#include "frame_capture.hpp"
#include "golden.hpp"
#include "graph/graph_model.hpp"
#include "image_probes.hpp"
#include "rt_ao.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

using namespace pathlet;

namespace {

const glm::ivec2 kSize{192, 144};
constexpr float kWidth = 0.5f;  // the fixture graph's line width

std::string source(const std::string& rel) { return std::string(PATHLET_SOURCE_DIR) + "/" + rel; }
Runtime& rt() { return test_runtime({PATHLET_TEST_PLUGIN_DIR}); }  // with the fragment fixture
const std::string kProbe = "passes/volume_ao/tests/graphs/vao_probe.json";

// Straight lines along x (times 0..10 s unless given), 81 points each. The scenes keep z their
// thinnest extent, so the framing camera looks along +z (smaller z is nearer) and sees them all.
constexpr float kLength = 12.0f;
struct Line {
    glm::vec3 at;  // y, z of the line; x runs over [0, length]
    float t0 = 0.0f, t1 = 10.0f;
    float length = kLength;
};
Scene straight_lines(const std::vector<Line>& lines) {
    Scene s;
    s.source = "vao-test";
    for (const Line& l : lines) {
        LineRange r{uint32_t(s.lines.position.size()), 81};
        for (int k = 0; k <= 80; ++k) {
            const float u = float(k) / 80.0f;
            s.lines.position.push_back(glm::vec3(l.length * u, l.at.y, l.at.z));
            s.lines.time.push_back(l.t0 + (l.t1 - l.t0) * u);
            s.lines.velocity.push_back({1.0f, 0.0f, 0.0f});
        }
        s.lines.lines.push_back(r);
    }
    return s;
}

Frame render(const Scene& scene, std::vector<std::string> sets = {}, double time = 10.0,
             const std::vector<std::string>& names = {"ao", "normal_depth", "line_id"}) {
    RenderOptions o;
    o.graph_path = source(kProbe);
    o.size = kSize;
    o.sets = std::move(sets);
    o.time.start = time;
    Frame f = render_frame(rt(), scene, o, names);
    if (const char* dir = std::getenv("PATHLET_VAO_TEST_DUMP")) {  // to look at the AO
        static int k = 0;
        write_image(std::string(dir) + "/ao_" + std::to_string(k++) + ".png", f["ao"]);
    }
    return f;
}

// Mean AO over the pixels where line `id` is in front.
double mean_ao_of_line(const Frame& f, int id, const std::string& ao = "ao", const std::string& ids = "line_id") {
    double sum = 0;
    size_t n = 0;
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x)
            if (int(f[ids].at(x, y, 0)) == id) sum += f[ao].at(x, y, 0), ++n;
    EXPECT_GT(n, 20u) << "line " << id << " hardly visible";
    return n ? sum / double(n) : 1.0;
}

// The ray-traced AO of `pathlet quality` per pixel of line `id` (every line with id < 0): from
// where the pixel's ray meets its line's round tube, cosine rays of 10 line widths against the
// tubes of the other lines; -1 where the line is not in front.
std::vector<double> rt_ao_per_pixel(const Frame& f, const Scene& scene, int id, int rays = 512) {
    std::vector<quality::Tube> tubes;
    for (size_t li = 0; li < scene.lines.lines.size(); ++li) {
        quality::Tube t;
        t.radius = 0.5f * kWidth;
        t.id = int(li);
        const LineRange r = scene.lines.lines[li];
        for (uint32_t i = r.first; i < r.first + r.count; ++i) t.points.push_back(scene.lines.position[i]);
        tubes.push_back(t);
    }
    quality::RayTracedAo rt(tubes);
    const Camera& cam = f.camera;
    const glm::mat4 inv_view = glm::inverse(cam.view);
    const glm::vec3 eye_at(inv_view[3]);
    std::vector<double> out(size_t(kSize.x) * size_t(kSize.y), -1.0);
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) {
            const int line = int(f["line_id"].at(x, y, 0));
            if (line < 0 || (id >= 0 && line != id)) continue;
            const float nx = (x + 0.5f) / kSize.x * 2 - 1, ny = 1 - (y + 0.5f) / kSize.y * 2;
            const glm::vec3 ray = glm::normalize(glm::mat3(inv_view) * glm::vec3(nx / cam.proj[0][0], ny / cam.proj[1][1], -1));
            glm::vec3 p, n;
            if (!rt.surface_of(line, eye_at, ray, p, n)) continue;
            out[size_t(y) * size_t(kSize.x) + size_t(x)] =
                rt.ambient(p + n * (0.05f * kWidth), n, rays, 10.0f * kWidth, uint32_t(y * kSize.x + x + 1), line);
        }
    return out;
}
double mean_rt_ao_of_line(const Frame& f, const Scene& scene, int id) {
    double sum = 0;
    size_t count = 0;
    for (double v : rt_ao_per_pixel(f, scene, id))
        if (v >= 0) sum += v, ++count;
    return count ? sum / double(count) : 1.0;
}

// A bed of lines: a front row 1.2 line widths apart and a row behind it offset by half a step;
// line 0 (front row, middle) deep in it, line 1 at its edge, line 2 alone far to the side.
Scene bundle_scene() {
    std::vector<Line> lines{{{0, 0, 0}}, {{0, 6 * 0.6f, 0}}, {{0, 16.0f, 0}}};
    for (int j = -6; j <= 5; ++j)
        if (j != 0) lines.push_back({{0, 0.6f * float(j), 0}});
    for (int j = -6; j <= 5; ++j) lines.push_back({{0, 0.6f * (float(j) + 0.5f), 0.6f}});
    return straight_lines(lines);
}

}  // namespace

// The line's own tube is left out: a straight line alone is open, every pixel of it; at the
// phantom's voxel size (grid 34 here: 1.4 radii, where the tube's own density reaches the
// rays) and at a fine one.
class IsolatedLine : public ::testing::TestWithParam<int> {};
INSTANTIATE_TEST_SUITE_P(VolumeAo, IsolatedLine, ::testing::Values(34, 96));
TEST_P(IsolatedLine, IsUnoccludedByItself) {
    const Scene scene = straight_lines({{{0, 0, 0}}, {{0, 8.0f, 0}}});  // a second line, beyond the reach
    const Frame f = render(scene, {"grid=" + std::to_string(GetParam())});
    double lowest = 1.0;
    size_t n = 0;
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x)
            if (int(f["line_id"].at(x, y, 0)) >= 0) lowest = std::min(lowest, double(f["ao"].at(x, y, 0))), ++n;
    EXPECT_GT(n, 200u);
    EXPECT_GT(lowest, 0.97) << "a line occludes itself";
    // Background: exactly 1, and no NaN anywhere.
    EXPECT_FALSE(has_nan(f["ao"]));
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x)
            if (int(f["line_id"].at(x, y, 0)) < 0) {
                ASSERT_EQ(f["ao"].at(x, y, 0), 1.0f) << x << "," << y;
            }
}

// Deep in the bed < at its edge < alone, in the order the ray-traced AO gives them and on its
// scale; per pixel, the estimate follows the reference (the targets of `pathlet quality`).
TEST(VolumeAo, BundleDarkerThanOutsideInTheRayTracedOrder) {
    const Scene scene = bundle_scene();
    const Frame f = render(scene);
    double vao[3], rt[3];
    for (int id = 0; id < 3; ++id) {
        vao[id] = mean_ao_of_line(f, id);
        rt[id] = mean_rt_ao_of_line(f, scene, id);
        std::printf("probe %d: volume AO %.3f, ray-traced %.3f\n", id, vao[id], rt[id]);
        EXPECT_NEAR(vao[id], rt[id], 0.06) << "line " << id;
    }
    EXPECT_LT(rt[0], rt[1]);
    EXPECT_LT(rt[1], rt[2]);
    EXPECT_LT(vao[0] + 0.05, vao[1]) << "deep in the bed should be darker than at its edge";
    EXPECT_LT(vao[1], vao[2]) << "the edge should be darker than a line alone";
    EXPECT_GT(vao[2], 0.97);
    // Every covered pixel of the bed: correlation and mean error against the reference.
    // The front row (the back row shows only in 0.1-wide crevices the grid cannot resolve:
    // ray-traced 0.1, volume 0.3; see the README's limits).
    std::vector<double> a, b;
    for (int id = 3; id < 3 + 11; ++id) {
        a.push_back(mean_ao_of_line(f, id));
        b.push_back(mean_rt_ao_of_line(f, scene, id));
        std::printf("line %d: volume AO %.3f, ray-traced %.3f\n", id, a.back(), b.back());
    }

    double ma = 0, mb = 0, mae = 0;
    for (size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i], mae += std::fabs(a[i] - b[i]);
    ma /= double(a.size()), mb /= double(b.size()), mae /= double(a.size());
    double cov = 0, va = 0, vb = 0;
    for (size_t i = 0; i < a.size(); ++i) cov += (a[i] - ma) * (b[i] - mb), va += (a[i] - ma) * (a[i] - ma), vb += (b[i] - mb) * (b[i] - mb);
    EXPECT_GT(cov / std::sqrt(va * vb), 0.8) << "per-line means of the bed against the ray-traced AO";
    EXPECT_LT(mae, 0.06);
}

// Rays in the line's cross-section with the rest of the hemisphere integrated for parallel
// neighbours (rays=section, the default) follow the ray-traced AO of the bed closer, pixel by
// pixel, than as many rays over the whole hemisphere.
TEST(VolumeAo, SectionRaysFollowTheRayTracedAoCloserThanAsManyHemisphereRays) {
    const Scene scene = bundle_scene();
    const Frame section = render(scene, {"volume_ao.directions=8"});
    const Frame hemisphere = render(scene, {"volume_ao.directions=8", "volume_ao.rays=hemisphere"});
    const std::vector<double> ref = rt_ao_per_pixel(section, scene, -1, 256);
    double err_section = 0, err_hemisphere = 0;
    size_t n = 0, occluded = 0;
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) {
            const double r = ref[size_t(y) * size_t(kSize.x) + size_t(x)];
            if (r < 0 || int(hemisphere["line_id"].at(x, y, 0)) != int(section["line_id"].at(x, y, 0))) continue;
            err_section += std::fabs(section["ao"].at(x, y, 0) - r);
            err_hemisphere += std::fabs(hemisphere["ao"].at(x, y, 0) - r);
            occluded += r < 0.8;
            ++n;
        }
    ASSERT_GT(n, 1000u);
    ASSERT_GT(occluded, 300u) << "the bed must be occluded, or the comparison says nothing";
    err_section /= double(n), err_hemisphere /= double(n);
    std::printf("bed, per pixel against the ray-traced AO: MAE section rays %.4f, hemisphere rays %.4f\n", err_section,
                err_hemisphere);
    EXPECT_LT(err_section, 0.85 * err_hemisphere);
    EXPECT_LT(err_section, 0.08);
}

// The volume holds the window's pathlets only: neighbours whose times lie outside it cast
// nothing (the same geometry with its times inside the window does), and a neighbour half in
// the window occludes along that half only (segments clipped in time, as the kit draws them).
TEST(VolumeAo, FollowsTheTimeWindow) {
    auto scene_with_neighbour_times = [](float t0, float t1) {
        // Beside the line and a little nearer the camera, without hiding it.
        return straight_lines({{{0, 0, 0}}, {{0, 0.5f, -0.45f}, t0, t1}, {{0, -0.5f, -0.45f}, t0, t1}, {{0, 8.0f, 0}}});
    };
    const Frame inside = render(scene_with_neighbour_times(0.0f, 10.0f));
    const Frame outside = render(scene_with_neighbour_times(20.0f, 30.0f));
    const double in = mean_ao_of_line(inside, 0), out = mean_ao_of_line(outside, 0);
    std::printf("neighbours in the window %.3f, outside %.3f\n", in, out);
    EXPECT_LT(in, out - 0.1) << "the neighbours in the window occlude";
    EXPECT_GT(out, 0.97) << "neighbours outside the window must cast nothing";
    // Neighbours with times 5..15 at t = 10 (window 10 s): their first halves are in the window.
    const Frame half = render(scene_with_neighbour_times(5.0f, 15.0f));
    double sum[2] = {0, 0};
    size_t n[2] = {0, 0};
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x)
            if (int(half["line_id"].at(x, y, 0)) == 0) {
                const int side = y < kSize.y / 2 ? 0 : 1;  // the lines run up the image (framing)
                sum[side] += half["ao"].at(x, y, 0), ++n[side];
            }
    ASSERT_GT(n[0], 20u);
    ASSERT_GT(n[1], 20u);
    const double lo = std::min(sum[0] / double(n[0]), sum[1] / double(n[1]));
    const double hi = std::max(sum[0] / double(n[0]), sum[1] / double(n[1]));
    std::printf("half in the window: %.3f and %.3f\n", lo, hi);
    EXPECT_LT(lo, in + 0.05) << "where the neighbours are in the window";
    EXPECT_GT(hi, 0.97) << "where they are not";
}

// Where a neighbour ends (a pathlet's head, which moves on every frame), the AO ramps along
// the line as the ray-traced AO does, over a distance like the neighbour's: the section rays
// are tilted along the line. Rays in the section alone switched within a voxel or two, and a
// head moving by flickered. The ramp's width: the rows of line 0 (they run up the image)
// between 20 % and 80 % of the way from the occluded to the open AO.
TEST(VolumeAo, RampsWhereANeighbourEndsAsTheRayTracedAoDoes) {
    // Neighbours along the first half of line 0 (a pathlet's head stops there as a line's end does).
    const Scene scene = straight_lines({{{0, 0, 0}}, {{0, 0.5f, -0.45f}, 0.0f, 10.0f, kLength / 2}, {{0, -0.5f, -0.45f}, 0.0f, 10.0f, kLength / 2}});
    const Frame f = render(scene);
    const std::vector<double> ref = rt_ao_per_pixel(f, scene, 0, 1024);
    // Line 0's mean per row, the rows of its whole length (they run up the image).
    auto profile = [&](bool traced) {
        std::vector<double> row;
        for (int y = 0; y < kSize.y; ++y) {
            double sum = 0;
            int n = 0;
            for (int x = 0; x < kSize.x; ++x) {
                const size_t i = size_t(y) * size_t(kSize.x) + size_t(x);
                if (int(f["line_id"].at(x, y, 0)) != 0 || ref[i] < 0) continue;
                sum += traced ? ref[i] : double(f["ao"].at(x, y, 0));
                ++n;
            }
            if (n >= 2) row.push_back(sum / n);
        }
        return row;
    };
    // Rows between 10 % and 90 % of the way from the occluded end's level to the open end's.
    auto ramp_rows = [](const std::vector<double>& row) {
        const size_t ends = 20;
        EXPECT_GT(row.size(), 4 * ends) << "line 0 hardly visible";
        if (row.size() <= 4 * ends) return 0;
        double a = 0, b = 0;
        for (size_t i = 0; i < ends; ++i) a += row[i] / ends, b += row[row.size() - 1 - i] / ends;
        EXPECT_GT(std::fabs(a - b), 0.1) << "the neighbours must occlude, or the ramp says nothing";
        int inside = 0;
        for (double v : row) {
            const double u = (v - std::min(a, b)) / std::fabs(a - b);
            inside += u > 0.1 && u < 0.9;
        }
        return inside;
    };
    const int rows = ramp_rows(profile(false)), rows_traced = ramp_rows(profile(true));
    std::printf("ramp where the neighbours end: %d rows, ray-traced %d rows\n", rows, rows_traced);
    EXPECT_GE(rows, rows_traced / 2) << "the AO switches where the neighbours end";
    EXPECT_LE(rows, 2 * rows_traced);
}

// The same frame twice: the same AO, bit for bit (integer splat, fixed directions).
TEST(VolumeAo, Deterministic) {
    const Scene scene = bundle_scene();
    const Frame a = render(scene), b = render(scene);
    EXPECT_EQ(max_abs_difference(a["ao"], b["ao"]), 0.0f);
}

// The density's 3D texture made by a dispatch (a GPU's default: no pixel-buffer upload the
// driver might convert on the CPU) is the upload's (llvmpipe's default), to float rounding.
TEST(VolumeAo, TheDensityCopiedByADispatchIsTheUploadsTexture) {
    const Scene scene = bundle_scene();
    auto copy = [](const std::string& how) {
        std::vector<std::string> sets;
        for (const char* pass : {"volume_ao", "resolve_list", "fragment_probe"})
            sets.push_back(std::string(pass) + ".density_copy=" + how);
        return sets;
    };
    const std::vector<std::string> names = {"ao", "front_ao", "fragment_ao"};
    const Frame up = render(scene, copy("upload"), 10.0, names), gpu = render(scene, copy("compute"), 10.0, names);
    size_t occluded = 0;
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) occluded += up["ao"].at(x, y, 0) < 0.9f;
    EXPECT_GT(occluded, 100u) << "the bundle must be occluded, or equal images say nothing";
    for (const auto& n : names) EXPECT_LT(max_abs_difference(up[n], gpu[n]), 1e-4f) << n;
}

// Every OIT fragment's own AO (fill_list's records, resolve_list) is the per-pixel estimate
// of the same surface: fp16 G-buffer against 32-bit node depth, packed normals.
TEST(VolumeAo, PerFragmentUnderOitMatchesPerPixel) {
    const Scene scene = bundle_scene();
    const Frame f = render(scene, {}, 10.0, {"ao", "line_id", "front_ao", "front_line_id"});
    double diff = 0, worst = 0;
    size_t n = 0, occluded = 0;
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) {
            const int id = int(f["line_id"].at(x, y, 0));
            if (id < 0 || id != int(f["front_line_id"].at(x, y, 0))) continue;
            const double d = std::fabs(double(f["ao"].at(x, y, 0)) - double(f["front_ao"].at(x, y, 0)));
            diff += d, worst = std::max(worst, d), ++n;
            occluded += f["ao"].at(x, y, 0) < 0.9f;
        }
    ASSERT_GT(n, 1000u);
    EXPECT_GT(occluded, 100u) << "the bundle must be occluded, or equal images say nothing";
    EXPECT_LT(diff / double(n), 0.01);
    EXPECT_LT(worst, 0.1);
}

// A line pass's own fragment stage (the kit's line_volume_ao_fragment, as a fade plugin would
// use it) computes what volume_ao computes from the G-buffer of the same fragments.
TEST(VolumeAo, KitFragmentFunctionMatchesPerPixel) {
    const Frame f = render(bundle_scene(), {}, 10.0, {"ao", "line_id", "fragment_ao"});
    double diff = 0, worst = 0;
    size_t n = 0, occluded = 0;
    for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) {
            if (int(f["line_id"].at(x, y, 0)) < 0) {
                ASSERT_EQ(f["fragment_ao"].at(x, y, 0), 1.0f) << "background at " << x << "," << y;
                continue;
            }
            const double d = std::fabs(double(f["ao"].at(x, y, 0)) - double(f["fragment_ao"].at(x, y, 0)));
            diff += d, worst = std::max(worst, d), ++n;
            occluded += f["ao"].at(x, y, 0) < 0.9f;
        }
    ASSERT_GT(n, 1000u);
    EXPECT_GT(occluded, 100u) << "the bundle must be occluded, or equal images say nothing";
    EXPECT_LT(diff / double(n), 0.01);
    EXPECT_LT(worst, 0.1);
}

// The graph's picture on the shared test bundle (one golden; the rest are properties).
TEST(VolumeAo, Variant1VaoGolden) {
    RenderOptions o;
    o.graph_path = source("graphs/variant1_vao.json");
    o.size = {160, 120};
    o.sets = {"window=0", "line_width=0.15", "overlay=false"};
    o.time.start = 5.0;
    const Frame f = render_frame(rt(), helix_bundle_scene(), o, {"final"});
    EXPECT_TRUE(matches_golden(f["final"], source("passes/volume_ao/tests/goldens/variant1_vao.png")));
}

// grid 0 and 4096 (4096^3 voxels) and a negative reach are errors naming the parameter; a grid
// the cap (2^26 voxels) cannot hold is an error in setup that names the cap.
TEST(VolumeAo, BadParametersAreClearErrors) {
    for (const char* text : {"grid=0", "grid=4096", "reach=-1", "line_density.grid=0", "volume_ao.reach=-2"}) {
        const std::string set = text;
        GraphFile g = parse_graph_file(source(kProbe));
        std::vector<Diagnostic> diags;
        apply_overrides(g, {set}, rt().registry, diags);
        for (const Diagnostic& d : validate_graph(g, rt().registry)) diags.push_back(d);
        ASSERT_FALSE(diags.empty()) << set << " was accepted";
        const std::string name = set.substr(set.find('.') == std::string::npos ? 0 : set.find('.') + 1,
                                            set.find('=') - (set.find('.') == std::string::npos ? 0 : set.find('.') + 1));
        EXPECT_NE(diags[0].str().find(name), std::string::npos) << diags[0].str();
    }
    // A cube of lines: grid 1024 would need 1028^3 voxels.
    const Scene cube = straight_lines({{{0, 0, 0}}, {{0, kLength, kLength}}});
    try {
        render(cube, {"grid=1024"});
        FAIL() << "grid 1024 over a cube was accepted";
    } catch (const std::exception& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("line_density"), std::string::npos) << what;
        EXPECT_NE(what.find("cap of 67108864 voxels"), std::string::npos) << what;
    }
}

// The volume's memory follows `grid` and stops at the cap; `graph --plan` reports it.
TEST(VolumeAo, MemoryIsBoundedByTheCap) {
    auto density_bytes = [](const std::string& set) {
        GraphFile g = parse_graph_file(source(kProbe));
        std::vector<Diagnostic> diags;
        apply_overrides(g, {set}, rt().registry, diags);
        const CompiledGraph cg = compile_graph(g, rt().registry, kSize);
        return cg.resources[size_t(cg.find_resource("density"))].bytes;
    };
    EXPECT_EQ(density_bytes("grid=96"), 48u + 4u * 100 * 100 * 100);
    EXPECT_EQ(density_bytes("grid=256"), 48u + 4u * 260 * 260 * 260);
    EXPECT_EQ(density_bytes("grid=1024"), 48u + 4u * (size_t(1) << 26));
    // What a frame uses: the box the data needs, reported with the pass's stats.
    const Frame f = render(bundle_scene());
    EXPECT_GT(f.stats.at("voxels"), 1000.0);
    EXPECT_LT(f.stats.at("voxels"), 100.0 * 100 * 100);
}
