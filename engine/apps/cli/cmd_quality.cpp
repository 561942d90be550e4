// pathlet quality [GRAPH...]: measures of LineAO quality at a fixed camera (issue 13):
// temporal flicker against the change of the geometry, and the error of the screen-space AO
// against a ray-traced AO of the same frame (Embree, tube geometry of the visible pathlets).
// The graph is run with two extra bindings added in memory: gbuffer's line_id and bilateral's
// ao_smooth (the AO that reaches the image), read back after every frame.
#include "commands.hpp"
#include "common_options.hpp"
#include "executor.hpp"
#include "image_io.hpp"
#include "renderer.hpp"
#include "util/atomic_file.hpp"
#include "util/text.hpp"

#include "ao_error.hpp"
#include "flicker.hpp"
#include "rt_ao.hpp"

#include <cstdio>
#include <filesystem>

namespace pathlet::cli {
namespace {

namespace fs = std::filesystem;
using quality::FrameSample;

// What the patched graph binds, or why it cannot be measured.
struct Patch {
    std::string why_not;  // non-empty: not measurable
    std::string line_id, normal_depth, ao;
};

// Binds gbuffer.line_id and the AO that reaches the image, and keeps them (outputs without
// capture) so the compiler does not cull them.
Patch patch_graph(json& g) {
    Patch p;
    json* gbuffer = nullptr;
    json* bilateral = nullptr;
    json* lineao = nullptr;
    for (json& pass : g["passes"]) {
        const std::string type = pass.value("type", "");
        if (type == "bilateral") bilateral = &pass;
        if (type == "lineao") lineao = &pass;
    }
    if (!lineao) return {"no AO in this graph (no lineao pass)"};
    // The G-buffer is whichever line pass writes what lineao reads as normal_depth: gbuffer,
    // geometric_fade, fade_core or a fade of yours (every kit G-buffer pass has line_id).
    const json& lin = (*lineao)["inputs"];
    const std::string nd = lin.contains("normal_depth") ? lin["normal_depth"].get<std::string>() : "";
    for (json& pass : g["passes"])
        if (pass.contains("outputs") && pass["outputs"].value("normal_depth", "") == nd && !nd.empty()) gbuffer = &pass;
    if (!gbuffer) return {"no G-buffer pass feeding lineao (no line id and depth per pixel to compare frames by)"};
    json& outs = (*gbuffer)["outputs"];
    if (!outs.contains("normal_depth")) return {"gbuffer's normal_depth is not bound"};
    p.normal_depth = outs["normal_depth"];
    if (outs.contains("line_id")) {
        p.line_id = outs["line_id"];
    } else {
        p.line_id = "quality_line_id";
        outs["line_id"] = p.line_id;
        g["resources"][p.line_id] = {{"format", "r32i"}};
    }
    if (bilateral && (*bilateral)["outputs"].contains("ao_smooth")) {
        p.ao = (*bilateral)["outputs"]["ao_smooth"];  // already bound (variant2_oit_ao)
    } else if (bilateral) {
        p.ao = "quality_ao";
        (*bilateral)["outputs"]["ao_smooth"] = p.ao;
        g["resources"][p.ao] = {{"format", "r16f"}};
    } else {
        p.ao = (*lineao)["outputs"]["ao"];
    }
    for (const std::string& r : {p.line_id, p.normal_depth, p.ao}) g["outputs"].push_back({{"resource", r}});
    return p;
}

// Reads a texture's first channel, top row first (as read_texture does).
std::vector<int32_t> read_ids(const Texture& t) {
    std::vector<int32_t> v(size_t(t.width) * t.height);
    glGetTextureImage(t.id, 0, GL_RED_INTEGER, GL_INT, GLsizei(v.size() * 4), v.data());
    std::vector<int32_t> flipped(v.size());
    for (int y = 0; y < t.height; ++y)
        std::copy_n(&v[size_t(t.height - 1 - y) * t.width], t.width, &flipped[size_t(y) * t.width]);
    return flipped;
}

struct Captured {
    FrameSample sample;
    std::vector<glm::vec3> normal;  // view space
    double time = 0;
};

// Tubes of the visible pathlets at time t: the points of each line within [t - window, t].
std::vector<quality::Tube> visible_tubes(const Pathlines& lines, double t, double window, float radius) {
    std::vector<quality::Tube> tubes;
    for (const LineRange& r : lines.lines) {
        quality::Tube tube;
        tube.radius = radius;
        for (uint32_t i = r.first; i < r.first + r.count; ++i) {
            const double ti = lines.time[i];
            if (window <= 0 || (ti >= t - window && ti <= t)) tube.points.push_back(lines.position[i]);
        }
        if (tube.points.size() >= 2) tubes.push_back(std::move(tube));
    }
    return tubes;
}

// Ray-traced AO per covered pixel: the pixel's 3D point from its linear depth through the
// camera (exact inverse of engine/lines/shaders/line_common.glsl), its normal to world space.
std::vector<float> reference_ao(const Captured& c, const Camera& cam, const quality::RayTracedAo& rt, int rays,
                                float max_distance, float offset) {
    const FrameSample& f = c.sample;
    std::vector<float> out(f.size(), 1.0f);
    const glm::mat4 inv_view = glm::inverse(cam.view);
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const size_t i = size_t(y) * f.width + x;
            if (f.line_id[i] < 0) continue;
            const float nx = (x + 0.5f) / f.width * 2 - 1, ny = 1 - (y + 0.5f) / f.height * 2;  // top row first
            const float eye = cam.near_plane + f.depth[i] * (cam.far_plane - cam.near_plane);
            const glm::vec4 view(nx * eye / cam.proj[0][0], ny * eye / cam.proj[1][1], -eye, 1.0f);
            const glm::vec3 p = glm::vec3(inv_view * view);
            const glm::vec3 n = glm::normalize(glm::mat3(inv_view) * c.normal[i]);
            out[i] = rt.ambient(p + n * offset, n, rays, max_distance, uint32_t(i + 1));
        }
    return out;
}

void write_error_image(const std::string& path, const FrameSample& f, const std::vector<float>& err) {
    Image img;
    img.width = f.width;
    img.height = f.height;
    img.channels = 4;
    img.pixels.assign(f.size() * 4, 1.0f);
    for (size_t i = 0; i < f.size(); ++i) {
        const float e = std::min(1.0f, err[i] * 2.0f);  // 0.5 error = full red
        const bool line = f.line_id[i] >= 0;
        img.pixels[i * 4 + 0] = line ? 1.0f : 0.9f;
        img.pixels[i * 4 + 1] = line ? 1.0f - e : 0.9f;
        img.pixels[i * 4 + 2] = line ? 1.0f - e : 0.9f;
    }
    ensure_parent_dir(path);
    write_image(path, img);
}

int run(const std::vector<std::string>& argv) {
    Args a("quality",
           "Measures LineAO quality at a fixed camera over a time range: temporal flicker (mean frame-to-frame\n"
           "change of AO where the same line is seen at the same depth) against the change of the geometry,\n"
           "and the error (MAE, correlation) of the screen-space AO against a CPU ray-traced AO (Embree,\n"
           "tubes of the visible pathlets, cosine-weighted rays) of the last frame, with an error image.");
    RenderOptions opt;
    std::string graph = "variant1_lineao", out_dir = "out/quality";
    int rays = 256;
    float reach = 10.0f, tol = 0.002f;
    PluginOptions plugins;
    SceneOptions data;
    opt.time = parse_time_range("9:9.4:0.04");
    opt.size = {320, 180};
    a.positional("GRAPH", graph, "graph file or shipped graph name (default: variant1_lineao)", false)
        .option("time", opt.time, "A:B:STEP", "animation times (frames at A, A+STEP, ... <= B)");
    declare_size(a, opt.size, "output size in pixels");
    a.option("rays", rays, "N", "ray-traced AO: rays per pixel")
        .option("max-distance", reach, "WIDTHS", "ray-traced AO: ray length in line widths")
        .option("depth-tolerance", tol, "D", "flicker: largest change of linear depth that counts as unchanged")
        .option("out", out_dir, "DIR", "folder for the per-pixel error image");
    declare_sets(a, opt.sets);
    plugins.declare(a);
    data.declare(a);
    if (!a.parse(argv)) return 0;
    opt.graph_path = resolve_graph_path(graph);
    if (rays < 1) throw UsageError("--rays must be >= 1");
    opt.write_images = false;
    opt.quiet = true;
    opt.warmup = 1;

    json g = text::read_json_file(opt.graph_path, "graph file");
    const std::string name = g.value("name", fs::path(opt.graph_path).stem().string());
    Patch patch = patch_graph(g);
    if (!patch.why_not.empty()) {
        std::printf("%s: not measured: %s\n", name.c_str(), patch.why_not.c_str());
        return 0;
    }
    fs::create_directories(out_dir);
    const std::string patched = out_dir + "/." + name + ".quality.json";
    write_file_atomic(patched, g.dump(2));
    opt.graph_path = patched;

    // The patched copy is a temporary: gone however the run ends.
    struct Remove { std::string p; ~Remove() { std::error_code ec; fs::remove(p, ec); } } remove_patched{patched};
    Runtime rt;
    plugins.load(rt);
    Scene scene = data.load(true);
    std::vector<Captured> frames;
    const std::vector<double> times = opt.time.times();
    RenderResult res = render(rt, scene, opt, [&](const Executor& ex, size_t frame) {
        Captured c;
        c.time = times[std::min(frame, times.size() - 1)];
        const Texture ao = ex.texture(patch.ao), nd = ex.texture(patch.normal_depth), id = ex.texture(patch.line_id);
        const Image ai = read_texture(ao.id, ao.width, ao.height, 0, 1), ni = read_texture(nd.id, nd.width, nd.height, 0, 4);
        FrameSample& f = c.sample;
        f.width = ao.width;
        f.height = ao.height;
        f.line_id = read_ids(id);
        f.ao = ai.pixels;
        f.depth.resize(f.size());
        c.normal.resize(f.size());
        for (size_t i = 0; i < f.size(); ++i) {
            f.depth[i] = ni.pixels[i * 4 + 3];
            c.normal[i] = glm::vec3(ni.pixels[i * 4], ni.pixels[i * 4 + 1], ni.pixels[i * 4 + 2]);
            if (glm::dot(c.normal[i], c.normal[i]) < 0.01f) f.line_id[i] = -1;  // halo-less background
        }
        frames.push_back(std::move(c));
    });
    if (frames.size() < 2) throw UsageError("--time must give at least two frames");

    std::vector<FrameSample> samples;
    for (const Captured& c : frames) samples.push_back(c.sample);
    const quality::FlickerStats fl = quality::measure_flicker(samples, tol);

    const json& vars = res.compiled.variables;
    const double window = vars.contains("window") ? vars["window"].get<double>() : 1.0;
    float width = vars.contains("line_width") ? vars["line_width"].get<float>() : 0.0f;
    const Bounds b = scene.lines.bounds();
    if (width <= 0) width = GpuScene::auto_line_width(b);
    const Captured& last = frames.back();
    const Camera cam = frame_bounds(scene.bounds(), opt.size);
    quality::RayTracedAo tracer(visible_tubes(scene.lines, last.time, window, 0.5f * width));
    const std::vector<float> ref = reference_ao(last, cam, tracer, rays, reach * width, 0.05f * width);
    const quality::AoError err = quality::measure_ao_error(last.sample, ref);
    const std::string image = out_dir + "/" + name + "_error.png";
    write_error_image(image, last.sample, err.abs_error);

    std::printf("%s: %zu frames %dx%d, t=%.2f..%.2f\n", name.c_str(), frames.size(), opt.size.x, opt.size.y,
                frames.front().time, last.time);
    std::printf("  flicker: mean |dAO| %.5f over %zu stable pixels; geometry change %.3f of covered pixels\n",
                fl.ao_flicker, fl.stable_pixels, fl.geometry_change);
    std::printf("  vs ray-traced AO (%d rays/px, reach %.3g = %.0f line widths, %zu tube segments): MAE %.4f, "
                "correlation %.3f over %zu px\n",
                rays, reach * width, reach, tracer.segments(), err.mae, err.correlation, err.pixels);
    std::printf("  error image: %s\n", image.c_str());
    return 0;
}

PATHLET_COMMAND("quality", "LineAO quality: temporal flicker and error against ray-traced AO", run);

}  // namespace
}  // namespace pathlet::cli
