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

// The largest difference of two 8-bit pictures in levels, over every channel; a diff image
// (the differences times 32) goes to the golden failure folder when it exceeds `max_levels`.
int max_levels(const Image& a, const Image& b, const std::string& name, int limit) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
    Image diff = a;
    int worst = 0;
    for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
        const int d = std::abs(int(to_unorm8(a.pixels[i])) - int(to_unorm8(b.pixels[i])));
        worst = std::max(worst, d);
        diff.pixels[i] = std::min(1.0f, float(d) * 32.0f / 255.0f);
    }
    for (size_t i = 3; i < diff.pixels.size(); i += 4) diff.pixels[i] = 1.0f;
    if (worst > limit) write_image(golden_failure_dir() + "/points_" + name + "_diff.png", diff);
    return worst;
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
        if (layout == GpuScene::PointLayout::quantised) EXPECT_LE(m.per_point(), 32.0);
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
    EXPECT_LE(worst_arc, 0.5f + 1e-2f) << "steps of the longest line's arc length";
    GpuScene exact;
    exact.upload(scene, GpuScene::PointLayout::exact);
    EXPECT_EQ(glm::vec3(exact.stored_point(7)), scene.lines.position[7]);
}

// Every kind of line pipeline (G-buffer and LineAO, lists, ISL, volume AO through the density),
// whole lines and a window: the quantised points draw what exact floats draw, within 1/255.
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
        const int levels = max_levels(exact["final"], quantised["final"], name, 1);
        EXPECT_LE(levels, 1) << name << ": quantised against exact, levels of 255";
        std::printf("%s: max %d levels\n", name.c_str(), levels);
    }
}
