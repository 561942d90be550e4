// Fullscreen passes with a compute version (PassTypeBuilder::compute_version(), parameter
// `impl`): the compute port draws what the fragment version draws, on real frames of the small
// phantom (a close camera, so lines cross the image border, at 333x217: no multiple of the
// 8x8 work group), every parameter path of each port, every resource of the frame compared
// (allowed: 0.5/255 RMS and no pixel off by more than 1/255; measured: identical); `auto` picks
// the fragment version on this llvmpipe context and follows auto_impl's rule for other renderer
// strings; every output a compute version writes has a format image load/store accepts; the
// SDK's dispatch on a probe pass covers exactly its rectangle, and its misuse is a clear error.
#include "camera.hpp"
#include "executor.hpp"
#include "frame_capture.hpp"
#include "golden.hpp"
#include "image_probes.hpp"

#include <pathlet/gl_limits.hpp>
#include <pathlet/shader.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

using namespace pathlet;

namespace {

const glm::ivec2 kOdd{333, 217};  // neither side a multiple of 8

// The default framing moved to 45 % of its distance: the vessel and its lines overfill the
// frame, so the passes' border handling (clamped neighbours, the screen rectangle reaching
// the edge) is exercised.
const std::string& close_camera() {
    static const std::string path = [] {
        const Camera c = frame_bounds(small_phantom_scene().bounds(), kOdd);
        const glm::vec3 eye = c.target + 0.45f * (c.eye - c.target);
        const std::string file = test_scratch_dir("compute_ports") + "/close_camera.json";
        std::ofstream(file) << "{\"keyframes\": [{\"time\": 0, \"eye\": [" << eye.x << ", " << eye.y << ", " << eye.z
                            << "], \"target\": [" << c.target.x << ", " << c.target.y << ", " << c.target.z
                            << "], \"up\": [" << c.up.x << ", " << c.up.y << ", " << c.up.z << "], \"fov\": "
                            << c.fov_y_deg << "}]}";
        return file;
    }();
    return path;
}

// Every texture a frame of the graph holds, each mip level of the pyramid too, and the
// `compute` stat per pass.
struct Capture {
    std::map<std::string, Image> images;  // "ao", "pyramid@2", ...
    std::map<std::string, double> compute;  // pass -> its kComputeStat
};

// The last of `frames` frames (0.04 s apart from t = 2 s, the middle of the small phantom's
// 0..4 s): more than one for passes with history.
Capture render_capture(const std::string& graph, const std::vector<std::string>& resources,
                       std::vector<std::string> sets, glm::ivec2 size = kOdd, bool close = true, int frames = 1) {
    RenderOptions o;
    o.graph_path = std::string(PATHLET_SOURCE_DIR) + "/graphs/" + graph + ".json";
    o.size = size;
    o.time.start = 2.0;
    o.time.end = 2.0 + 0.04 * (frames - 1) + 0.01;
    if (close) o.camera_path = close_camera();
    o.sets = std::move(sets);
    o.warmup = 0;
    o.write_images = false;
    o.quiet = true;
    o.keep = resources;
    Capture c;
    RenderResult res = render(test_runtime(), small_phantom_scene(), o, [&](const Executor& ex, size_t) {
        for (const auto& name : resources) {
            const Texture t = ex.texture(name);
            if (t.mips == 1) {
                c.images[name] = read_resource(t);
                continue;
            }
            for (int l = 0; l < t.mips; ++l)
                c.images[name + "@" + std::to_string(l)] =
                    read_texture(t.id, std::max(t.width >> l, 1), std::max(t.height >> l, 1), l, 4);
        }
    });
    for (const auto& p : res.profiler.passes())
        if (auto it = p.stats.find(kComputeStat); it != p.stats.end()) c.compute[p.name] = it->second;
    return c;
}

struct Difference {
    float max = 0;       // largest |a - b| of any channel (0..1 for 8-bit images)
    double rms = 0;      // over every channel of every pixel
    size_t pixels = 0;   // pixels with any channel different
    size_t border = 0;   // of those, on the image's outermost row or column
    std::string first;   // where the first few are ("x,y" from the top left)
};

Difference compare(const Image& a, const Image& b) {
    Difference d;
    if (a.width != b.width || a.height != b.height || a.channels != b.channels || a.pixels.size() != b.pixels.size() ||
        a.pixels.empty()) {  // nothing to compare is as far apart as can be, never "the same"
        ADD_FAILURE() << "images of " << a.width << "x" << a.height << "x" << a.channels << " and " << b.width << "x" << b.height
                      << "x" << b.channels;
        d.max = std::numeric_limits<float>::infinity();
        d.rms = std::numeric_limits<double>::infinity();
        return d;
    }
    d.max = max_abs_difference(a, b);
    double sum = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            bool differs = false;
            for (int ch = 0; ch < a.channels; ++ch) {
                const double e = double(a.at(x, y, ch)) - double(b.at(x, y, ch));
                sum += e * e;
                differs = differs || e != 0.0;
            }
            if (differs && d.pixels < 8) d.first += " " + std::to_string(x) + "," + std::to_string(y);
            d.pixels += differs;
            d.border += differs && (x == 0 || y == 0 || x == a.width - 1 || y == a.height - 1);
        }
    d.rms = std::sqrt(sum / double(std::max<size_t>(a.pixels.size(), 1)));
    return d;
}

// The images that explain a failure: both versions and |difference| x 64.
void dump(const std::string& tag, const Image& fragment, const Image& compute) {
    const std::string base = golden_failure_dir() + "/compute_ports_" + tag;
    ensure_parent_dir(base + ".fragment.png");
    auto png = [](Image img) {  // floats (depth, AO) as they are; clamped to 8 bits by the writer
        img.is_float = false;
        return img;
    };
    write_image(base + ".fragment.png", png(fragment));
    write_image(base + ".compute.png", png(compute));
    Image d = png(fragment);
    for (size_t i = 0; i < d.pixels.size(); ++i) d.pixels[i] = std::min(1.0f, 64.0f * std::fabs(fragment.pixels[i] - compute.pixels[i]));
    if (d.channels == 4)  // opaque, so a difference in colour alone shows
        for (size_t i = 3; i < d.pixels.size(); i += 4) d.pixels[i] = 1.0f;
    write_image(base + ".diff.png", d);
    ADD_FAILURE() << "wrote " << base << ".fragment.png, .compute.png, .diff.png";
}

// Renders the graph with `pass.impl=fragment` and `pass.impl=compute` (plus `sets`) and
// compares every resource: identical is expected (same shader, same arithmetic); the bound
// is 0.5/255 RMS with no pixel off by more than 1/255.
// Returns the fragment version's capture, for properties of the frame.
Capture expect_same(const std::string& graph, const std::string& pass, const std::vector<std::string>& resources,
                    const std::vector<std::string>& sets = {}, int frames = 1, bool close = true) {
    std::string tag = pass;
    for (const auto& s : sets) tag += "_" + s;
    SCOPED_TRACE(graph + ", " + tag);
    auto with = [&](const char* impl) {
        std::vector<std::string> s = sets;
        s.push_back(pass + ".impl=" + impl);
        return render_capture(graph, resources, s, kOdd, close, frames);
    };
    const Capture frag = with("fragment"), comp = with("compute");
    // Each run reports what ran: otherwise a compute run that silently drew with the fragment
    // version would compare equal.
    EXPECT_EQ(frag.compute.count(pass), 1u) << pass << " reports no '" << kComputeStat << "' stat";
    if (!frag.compute.count(pass) || !comp.compute.count(pass)) return frag;
    EXPECT_EQ(frag.compute.at(pass), 0.0);
    EXPECT_EQ(comp.compute.at(pass), 1.0);
    // The frame has lines on the image border (where neighbours are clamped): AO below 1 there.
    if (close && frag.images.count("ao")) {
        const Image& ao = frag.images.at("ao");
        int border_lines = 0;
        for (int y = 0; y < ao.height; ++y)
            for (int x = 0; x < ao.width; ++x)
                border_lines += (x == 0 || y == 0 || x == ao.width - 1 || y == ao.height - 1) && ao.at(x, y, 0) < 1.0f;
        EXPECT_GT(border_lines, 10) << "the close camera should put lines on the border";
    }
    for (const auto& [name, a] : frag.images) {
        const Image& b = comp.images.at(name);
        if (const char* dir = std::getenv("PATHLET_COMPUTE_PORTS_DUMP")) {  // to look at what is compared
            Image shown = b;
            shown.is_float = false;
            write_image(std::string(dir) + "/" + tag + "_" + name + ".png", shown);
        }
        const Difference d = compare(a, b);
        EXPECT_LE(d.rms, 0.5 / 255) << name << ": RMS " << d.rms * 255 << "/255";
        EXPECT_LE(d.max, 1.0f / 255 + 1e-6f) << name << ": max " << d.max * 255 << "/255 over " << d.pixels << " pixels ("
                                             << d.border << " on the border)";
        if (d.max > 0) {
            std::printf("[ compute ] %s %s: %zu pixels differ (%zu on the border; first at%s), max %.3g/255, RMS %.3g/255\n",
                        tag.c_str(), name.c_str(), d.pixels, d.border, d.first.c_str(), double(d.max) * 255, d.rms * 255);
            if (d.rms > 0.5 / 255 || d.max > 1.0f / 255 + 1e-6f) dump(tag + "_" + name, a, b);
        }
    }
    return frag;
}

// What variant1_lineao's fullscreen passes write, the pyramid's every level included.
const std::vector<std::string> kVariant1 = {"pyramid", "ao", "lit", "composed", "smooth", "final"};

}  // namespace

// ---- the SDK's helpers on a probe pass of the test's own ------------------------------------

namespace {

constexpr glm::ivec4 kProbeRect{10, 5, 50, 40};  // x0, y0, x1, y1 (GL's bottom-left origin, end exclusive)
enum class ProbeMode { rect, whole, dispatch_fragment };

// Writes probe.frag over kProbeRect (or the whole output), as the SDK's helpers do it;
// dispatch_fragment hands dispatch_fullscreen a fragment program (an error).
class ComputeProbe : public Pass {
public:
    void setup(PassContext& ctx) override {
        mode_ = ctx.params().e<ProbeMode>("mode");
        prog_ = mode_ == ProbeMode::dispatch_fragment ? &ctx.program({"fullscreen.vert", "probe.frag"})
                                                      : &ctx.fullscreen_program("probe.frag");
    }
    void execute(PassContext& ctx) override {
        const Texture out = ctx.texture("out");
        const float zero[4] = {0, 0, 0, 0};
        glClearTexImage(out.id, 0, GL_RGBA, GL_FLOAT, zero);
        const glm::ivec4 rect = mode_ == ProbeMode::whole ? glm::ivec4(0, 0, out.width, out.height) : kProbeRect;
        ctx.stat(kComputeStat, ctx.use_compute() ? 1.0 : 0.0);
        if (ctx.use_compute() || mode_ == ProbeMode::dispatch_fragment) {
            if (mode_ == ProbeMode::whole) ctx.dispatch_fullscreen(*prog_);
            else ctx.dispatch_fullscreen(*prog_, rect);
            return;
        }
        ctx.bind_framebuffer({"out"});
        prog_->use();
        glEnable(GL_SCISSOR_TEST);
        glScissor(rect.x, rect.y, rect.z - rect.x, rect.w - rect.y);
        ctx.draw_fullscreen();
    }

private:
    ShaderProgram* prog_ = nullptr;
    ProbeMode mode_ = ProbeMode::rect;
};

// The same without compute_version(): asking for its compute version is an error.
class UndeclaredProbe : public Pass {
public:
    void setup(PassContext& ctx) override { ctx.use_compute(); }
    void execute(PassContext&) override {}
};

Runtime& probe_runtime() {
    static Runtime& rt = [] () -> Runtime& {
        Runtime& r = test_runtime();
        r.registry.add(PassTypeBuilder("compute_probe", "the SDK's compute helpers under test")
                           .param_enum("mode", "rect", {"rect", "whole", "dispatch_fragment"}, "what to run")
                           .param_color("color", glm::vec3(0.2f, 0.6f, 0.0f), "colour written (red, green)")
                           .output_texture("out", "rgba8", "the probe's pixels")
                           .compute_version()
                           .make<ComputeProbe>());
        r.registry.add(PassTypeBuilder("compute_probe_undeclared", "use_compute() without compute_version()")
                           .output_texture("out", "rgba8", "nothing")
                           .make<UndeclaredProbe>());
        return r;
    }();
    return rt;
}

// The probe graph rendered at an odd size; `out` as GL stores it (rows bottom-up flipped to
// top-down by read_resource: row y of the image is GL row height-1-y).
Image render_probe(const std::vector<std::string>& sets, const std::string& type = "compute_probe") {
    const std::string dir = test_scratch_dir("compute_probe");
    std::ifstream in(std::string(PATHLET_TEST_SOURCE_DIR) + "/probe/probe.json");
    std::string graph((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string key = "\"type\": \"compute_probe\"";
    graph.replace(graph.find(key), key.size(), "\"type\": \"" + type + "\"");
    std::ofstream(dir + "/probe.json") << graph;
    std::filesystem::copy_file(std::string(PATHLET_TEST_SOURCE_DIR) + "/probe/probe.frag", dir + "/probe.frag",
                               std::filesystem::copy_options::overwrite_existing);
    RenderOptions o;
    o.graph_path = dir + "/probe.json";
    o.size = {61, 47};
    o.sets = sets;
    o.warmup = 0;
    o.write_images = false;
    o.quiet = true;
    o.keep = {"out"};
    Image img;
    render(probe_runtime(), small_phantom_scene(), o, [&](const Executor& ex, size_t) { img = read_resource(ex.texture("out")); });
    return img;
}

// Where the probe wrote: every pixel of `rect` holds (0.2, 0.6, x/255, y/255) in GL coordinates,
// every other pixel 0.
void expect_probe(const Image& img, glm::ivec4 rect) {
    int wrong = 0;
    std::string first;
    for (int row = 0; row < img.height; ++row)
        for (int x = 0; x < img.width; ++x) {
            const int y = img.height - 1 - row;
            const bool inside = x >= rect.x && x < rect.z && y >= rect.y && y < rect.w;
            const glm::vec4 want = inside ? glm::vec4(0.2f, 0.6f, float(x) / 255.0f, float(y) / 255.0f) : glm::vec4(0.0f);
            for (int c = 0; c < 4; ++c)
                if (std::fabs(img.at(x, row, c) - want[c]) > 0.6f / 255.0f) {
                    if (!wrong++) first = std::to_string(x) + "," + std::to_string(y);
                    break;
                }
        }
    EXPECT_EQ(wrong, 0) << "pixels not as expected, first at GL " << first;
}

}  // namespace

TEST(dispatch_fullscreen, CoversExactlyTheRectangleLikeTheScissoredDraw) {
    for (const char* impl : {"fragment", "compute"}) {
        SCOPED_TRACE(impl);
        expect_probe(render_probe({std::string("probe.impl=") + impl}), kProbeRect);
        expect_probe(render_probe({std::string("probe.impl=") + impl, "probe.mode=whole"}), {0, 0, 61, 47});
    }
}

TEST(dispatch_fullscreen, ErrorsNameThePassAndWhatIsMissing) {
    try {
        render_probe({"probe.mode=dispatch_fragment"});
        ADD_FAILURE() << "a fragment program was dispatched";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("'probe'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("needs a compute program"), std::string::npos) << e.what();
    }
    try {
        render_probe({}, "compute_probe_undeclared");
        ADD_FAILURE() << "use_compute() on a type without compute_version() passed";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("compute_version()"), std::string::npos) << e.what();
    }
}

// ---- auto's rule ------------------------------------------------------------------------------

TEST(impl_auto, SoftwareRasterizersGetFragmentGpusCompute) {
    for (const char* r : {"llvmpipe (LLVM 15.0.6, 256 bits)", "softpipe", "Software Rasterizer", "Mesa X11 swrast",
                          "SwiftShader Device (Subzero) (0x0000C0DE)", "zink Vulkan 1.3(llvmpipe (LLVM 15.0.6, 256 bits))",
                          "D3D12 (Microsoft Basic Render Driver)"}) {
        EXPECT_FALSE(software_rasterizer(r).empty()) << r;
        EXPECT_EQ(auto_impl(r), FullscreenImpl::fragment) << r;
    }
    // Hardware, LLVM-compiled shaders included (radeonsi names LLVM, not llvmpipe).
    for (const char* r : {"NVIDIA H200/PCIe/SSE2", "NVIDIA H100 80GB HBM3/PCIe/SSE2",
                          "AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.6, DRM 3.49, 6.1.0)",
                          "Mesa Intel(R) UHD Graphics 620 (KBL GT2)", "Apple M2"}) {
        EXPECT_EQ(software_rasterizer(r), "") << r;
        EXPECT_EQ(auto_impl(r), FullscreenImpl::compute) << r;
    }
}

// On this context (llvmpipe, as every GL test runs) the shipped graph's defaults run every
// port's fragment version.
TEST(impl_auto, ResolvesToFragmentOnThisLlvmpipeContext) {
    const std::string renderer = test_runtime().gl->renderer();
    ASSERT_NE(renderer.find("llvmpipe"), std::string::npos) << "the GL tests run on llvmpipe, not " << renderer;
    const Capture c = render_capture("variant1_lineao", {}, {}, {96, 64}, false);
    for (const char* pass : {"gauss_pyramid", "lineao", "bilateral", "edge_aa"}) {
        ASSERT_EQ(c.compute.count(pass), 1u) << pass;
        EXPECT_EQ(c.compute.at(pass), 0.0) << pass << " ran its compute version under impl=auto on " << renderer;
    }
}

// ---- every output a compute version writes is an image format ------------------------------

TEST(compute_ports, OutputsHaveImageFormats) {
    // GL 4.5 table 8.27 (image load/store formats), as the engine's format names; not sRGB,
    // not depth.
    const std::set<std::string> image_formats = {"r8",      "rg8",    "rgba8",  "r16f",     "rg16f",
                                                 "rgba16f", "r32f",   "rg32f",  "rgba32f",  "r32ui",
                                                 "rg32ui",  "rgba32ui", "r32i", "rgb10a2", "r11g11b10f"};
    int ports = 0;
    for (const PassTypeInfo* t : test_runtime().registry.all()) {
        if (!t->param("impl")) continue;
        ++ports;
        for (const PinDecl& p : t->pins)
            if (p.dir == PinDir::Output && p.kind == PinKind::Texture) {
                EXPECT_TRUE(image_formats.count(p.format)) << t->type << "." << p.name << " is " << p.format
                                                           << ", which image load/store cannot write";
            }
    }
    EXPECT_GE(ports, 6) << "gauss_pyramid, lineao, bilateral, edge_aa, volume_ao and temporal_ao have compute versions";
}

// ---- each port against its fragment version ------------------------------------------------

TEST(compute_ports, GaussPyramid) {
    expect_same("variant1_lineao", "gauss_pyramid", kVariant1);
    expect_same("variant1_lineao", "gauss_pyramid", kVariant1, {"gauss_pyramid.mode=box", "gauss_pyramid.copy_level0=true"});
}

TEST(compute_ports, LineAO) {
    expect_same("variant1_lineao", "lineao", kVariant1);
    expect_same("variant1_lineao", "lineao", kVariant1, {"lineao.resolution=half"});
}

TEST(compute_ports, Bilateral) {
    expect_same("variant1_lineao", "bilateral", kVariant1);
    expect_same("variant1_lineao", "bilateral", kVariant1, {"bilateral.separable=false"});
}

TEST(compute_ports, EdgeAA) {
    expect_same("variant1_lineao", "edge_aa", kVariant1);
    expect_same("variant1_lineao", "edge_aa", kVariant1, {"edge_aa.alpha=coverage"});
}

TEST(compute_ports, BilateralSmoothedAoOutput) {  // the optional ao_smooth, for OIT's per-fragment AO
    expect_same("variant2_oit_ao", "bilateral", {"ao_smooth", "lit", "final"});
}

TEST(compute_ports, VolumeAO) {  // with the hybrid's screen-space term too
    expect_same("variant1_vao", "volume_ao", {"ao", "lit", "final"});
    expect_same("variant1_hybrid", "volume_ao", {"ao", "final"});
}

TEST(compute_ports, TemporalAO) {
    // Three frames at the default framing: the third blends the reprojected history. (Seen from
    // the close camera temporal_ao finds no history: most pixels reproject off screen.)
    const Capture c = expect_same("variant1_stable", "temporal_ao", {"ao", "ao_acc", "lit", "final"}, {}, 3, false);
    // On lines (AO below 1), the accumulated term is not this frame's: history was blended in.
    const Image &ao = c.images.at("ao"), &acc = c.images.at("ao_acc");
    int on_lines = 0, blended = 0;
    for (int y = 0; y < ao.height; ++y)
        for (int x = 0; x < ao.width; ++x)
            if (ao.at(x, y, 0) < 1.0f) ++on_lines, blended += acc.at(x, y, 0) != ao.at(x, y, 0);
    EXPECT_GT(blended, on_lines / 4) << "little history was blended in (" << blended << " of " << on_lines << " pixels)";
}

// Every compute version within the GL 4.5 minimum limits (8 image units, 8 image uniforms and
// 16 samplers per stage, 8 combined outputs): the engine checks every program and numbers the
// units under PATHLET_GL_LIMITS=minimum, as a minimal driver would.
// Each port is compared with its fragment version there as above (expect_same: the picture,
// every resource, and the `compute` stat of what ran), the other ports of the graph on compute
// too, so the most units are in use at once.
TEST(compute_ports, WithinTheGlMinimum) {
    struct MinimumLimits {
        MinimumLimits() { ::setenv("PATHLET_GL_LIMITS", "minimum", 1); }
        ~MinimumLimits() { ::unsetenv("PATHLET_GL_LIMITS"); }
    } minimum;
    test_runtime();  // a current context to ask
    ASSERT_EQ(gl_limits().get(GL_MAX_IMAGE_UNITS), 8) << "PATHLET_GL_LIMITS=minimum is in effect";
    const std::vector<std::string> others = {"gauss_pyramid.impl=compute", "bilateral.impl=compute", "edge_aa.impl=compute"};
    std::vector<std::string> half = others;
    half.push_back("lineao.resolution=half");
    expect_same("variant1_lineao", "lineao", kVariant1, others);
    expect_same("variant1_lineao", "lineao", kVariant1, half);
    expect_same("variant2_oit_ao", "bilateral", {"ao_smooth", "lit", "final"});
    expect_same("variant1_hybrid", "volume_ao", {"ao", "final"}, {"bilateral.impl=compute", "edge_aa.impl=compute"});
    expect_same("variant1_stable", "temporal_ao", {"ao", "ao_acc", "lit", "final"}, {}, 3, false);
}

// ---- through the command line ----------------------------------------------------------------

// A shipped graph with every port switched to compute by --set draws the picture the defaults
// (fragment, on llvmpipe) draw: the PNG files are compared.
TEST(compute_ports, SetImplComputeOnTheCommandLine) {
    const std::string dir = test_scratch_dir("compute_ports_cli");
    auto run = [&](const std::string& name, const std::string& sets) {
        const std::string cmd = std::string(PATHLET_CLI) + " render variant3_geomfade --phantom small --time 2 --size 333x217 --quiet" +
                                " --out " + dir + "/" + name + sets + " > " + dir + "/" + name + ".log 2>&1";
        EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
        return read_image(dir + "/" + name + "/variant3_geomfade/00000.png");
    };
    const Image def = run("default", "");
    const Image comp = run("compute", " --set gauss_pyramid.impl=compute --set lineao.impl=compute"
                                      " --set bilateral.impl=compute --set edge_aa.impl=compute");
    const Difference d = compare(def, comp);
    EXPECT_EQ(d.max, 0.0f) << d.pixels << " pixels differ, RMS " << d.rms * 255 << "/255";
    if (d.max > 0) dump("cli", def, comp);
    // An impl that is none of the choices is refused, naming the choices.
    const std::string bad = std::string(PATHLET_CLI) + " render variant3_geomfade --phantom small --time 2 --size 64x64 --quiet --out " +
                            dir + "/bad --set lineao.impl=vulkan > " + dir + "/bad.log 2>&1";
    EXPECT_NE(std::system(bad.c_str()), 0);
    std::ifstream log(dir + "/bad.log");
    const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("auto, fragment, compute"), std::string::npos) << text;
}
