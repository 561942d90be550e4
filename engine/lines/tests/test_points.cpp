// The scene's line points on the GPU (GpuScene): the memory reported is the buffers' sizes, the
// quantised positions are decoded within a step of the lines' own box, and every line
// pipeline draws the same picture from them as from exact floats (within 1/255).
#include "frame_capture.hpp"
#include "golden.hpp"
#include "image_io.hpp"
#include "runtime.hpp"

#include <gtest/gtest.h>
#include <pathlet/gpu_scene.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

using namespace pathlet;

namespace {

const std::string kGraphs = std::string(PATHLET_SOURCE_DIR) + "/graphs/";

// The helix bundle with a wall a hundred times its size: a quantisation against the scene's
// box (wall included) instead of the lines' would be a hundred times coarser.
const Scene& bundle_in_a_big_wall() {
    static const Scene s = [] {
        Scene scene = helix_bundle_scene();
        Mesh wall;
        const Bounds b = scene.lines.bounds();
        const glm::vec3 c = 0.5f * (b.lo + b.hi), r = 100.0f * (b.hi - b.lo);
        wall.position = {c - r, c + glm::vec3(r.x, -r.y, -r.z), c + glm::vec3(-r.x, r.y, r.z), c + r};
        wall.index = {0, 1, 2, 1, 3, 2};
        scene.mesh = wall;
        return scene;
    }();
    return s;
}

GLint64 buffer_size(GLuint b) {
    GLint64 n = 0;
    glGetNamedBufferParameteri64v(b, GL_BUFFER_SIZE, &n);
    return n;
}

struct Layout {
    explicit Layout(const char* name) { setenv("PATHLET_POINT_LAYOUT", name, 1); }
    ~Layout() { unsetenv("PATHLET_POINT_LAYOUT"); }
};

// Pixels of two 8-bit pictures that differ by more than one level in some channel, and the
// largest difference; a diff image (the differences times 32) goes to the golden failure folder
// when more than `allowed` pixels differ.
struct Difference {
    size_t pixels = 0;
    int worst = 0;
};
Difference compare(const Image& a, const Image& b, const std::string& name, size_t allowed) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
    Image diff = a;
    Difference d;
    for (size_t p = 0; p * 4 < a.pixels.size() && p * 4 < b.pixels.size(); ++p) {
        int here = 0;
        for (size_t c = 0; c < 4; ++c) {
            const int levels = std::abs(int(to_unorm8(a.pixels[4 * p + c])) - int(to_unorm8(b.pixels[4 * p + c])));
            here = std::max(here, levels);
            diff.pixels[4 * p + c] = c == 3 ? 1.0f : std::min(1.0f, float(levels) * 32.0f / 255.0f);
        }
        d.pixels += here > 1;
        d.worst = std::max(d.worst, here);
    }
    if (d.pixels > allowed) {
        std::filesystem::create_directories(golden_failure_dir());
        write_image(golden_failure_dir() + "/points_" + name + "_diff.png", diff);
    }
    return d;
}

}  // namespace

TEST(points, MemoryReportedIsTheBuffersSizesAndAtMost32BytesAPointQuantised) {
    test_runtime();  // a GL context
    const Scene& scene = bundle_in_a_big_wall();
    for (GpuScene::PointLayout layout : {GpuScene::PointLayout::quantised, GpuScene::PointLayout::exact}) {
        GpuScene gpu;
        gpu.upload(scene, layout);
        const GpuScene::PointMemory m = gpu.point_memory();
        EXPECT_EQ(m.points, scene.lines.point_count());
        EXPECT_EQ(GLint64(m.positions), buffer_size(gpu.points_buffer()));
        EXPECT_EQ(GLint64(m.attributes), buffer_size(gpu.attributes_buffer()));
        EXPECT_EQ(GLint64(m.lod), buffer_size(gpu.lod_buffer()));
        EXPECT_EQ(GLint64(m.chunk_boxes), buffer_size(gpu.chunk_buffer()));
        EXPECT_EQ(m.chunks, gpu.chunks().chunks().size());
        const GpuScene::PointMemory without_gl = GpuScene::point_memory(m.points, m.chunks, layout);
        EXPECT_EQ(without_gl.total(), m.total());
        if (layout == GpuScene::PointLayout::quantised) { EXPECT_LE(m.per_point(), 32.0); }
        std::printf("%s: %.2f bytes a point\n", GpuScene::layout_name(layout), m.per_point());
    }
}

TEST(points, QuantisedPositionsAreWithinHalfAStepOfTheLinesBox) {
    test_runtime();
    const Scene& scene = bundle_in_a_big_wall();
    GpuScene gpu;
    gpu.upload(scene, GpuScene::PointLayout::quantised);
    const Bounds b = scene.lines.bounds();
    const glm::vec3 step = (b.hi - b.lo) / float((1 << 21) - 1);
    glm::vec3 worst(0.0f);
    float longest = 0.0f, worst_arc = 0.0f;
    std::vector<float> arc(scene.lines.point_count(), 0.0f);
    for (const LineRange& r : scene.lines.lines)
        for (uint32_t i = r.first + 1; i < r.first + r.count; ++i)
            arc[i] = arc[i - 1] + glm::length(scene.lines.position[i] - scene.lines.position[i - 1]), longest = std::max(longest, arc[i]);
    for (size_t i = 0; i < scene.lines.point_count(); ++i) {
        const glm::vec4 p = gpu.stored_point(i);
        worst = glm::max(worst, glm::abs(glm::vec3(p) - scene.lines.position[i]) / step);
        worst_arc = std::max(worst_arc, std::abs(p.w - arc[i]) / (longest / 65535.0f));
    }
    // Half a step, and the float arithmetic of the decoding (a few float steps at the box's far side).
    for (int a = 0; a < 3; ++a) EXPECT_LE(worst[a], 0.75f) << "axis " << a << ": steps of the lines' box";
    EXPECT_LE(worst_arc, 0.75f) << "steps of the longest line's arc length (summed here in float)";
    GpuScene exact;
    exact.upload(scene, GpuScene::PointLayout::exact);
    EXPECT_EQ(glm::vec3(exact.stored_point(7)), scene.lines.position[7]);
}

// Every kind of line pipeline (G-buffer and LineAO, lists, ISL, volume AO through the density),
// whole lines and a window: the quantised points draw what exact floats draw within 1/255, but
// for isolated pixels where two lines cross at the same depth or an edge passes a pixel's centre
// (a move of a few float steps flips them): at most 1 in 400 pixels (measured: 5 to 102 of
// 76,800), where the lines' positions quantised in the wall's box, a hundred times coarser,
// flip 530 to 2,033.
TEST(points, QuantisedPicturesMatchExactOnesWithinOneLevel) {
    const Scene& scene = bundle_in_a_big_wall();
    // Framed on the helices, not on the wall (the framing camera would take the whole scene).
    const std::string camera = write_square_on_camera(test_scratch_dir("points") + "/camera.json");
    struct Case {
        const char* graph;
        const char* window;
    };
    for (const Case c : {Case{"variant1_lineao", "0"}, Case{"variant1_lineao", "3"}, Case{"variant2_oit", "3"},
                         Case{"isl", "0"}, Case{"variant1_vao", "3"}, Case{"variant3_geomfade", "3"}}) {
        RenderOptions opt;
        opt.graph_path = kGraphs + c.graph + ".json";
        opt.sets = {"window=" + std::string(c.window), "wall=false", "overlay=false"};
        opt.size = {320, 240};
        opt.time.start = 6.0;
        opt.camera_path = camera;
        Frame exact, quantised;
        {
            Layout l("exact");
            exact = render_frame(test_runtime(), scene, opt, {"final"});
        }
        {
            Layout l("quantised");
            quantised = render_frame(test_runtime(), scene, opt, {"final"});
        }
        const std::string name = std::string(c.graph) + "_w" + c.window;
        const Image& e = exact["final"];
        const size_t allowed = size_t(e.width) * size_t(e.height) / 400;
        const Difference d = compare(e, quantised["final"], name, allowed);
        EXPECT_LE(d.pixels, allowed) << name << ": pixels more than 1/255 apart, quantised against exact";
        std::printf("%s: %zu pixels more than 1/255 apart (at most %d levels)\n", name.c_str(), d.pixels, d.worst);
    }
}
