// pathlet quality [GRAPH...]: measures of LineAO quality at a fixed camera (issue 13):
// temporal flicker against the change of the geometry, and the error of the screen-space AO
// against a ray-traced AO of the same frame (Embree, tube geometry of the visible pathlets).
// The graph is run with two extra bindings added in memory: gbuffer's line_id and bilateral's
// ao_smooth (the AO that reaches the image), read back after every frame.
#include "args.hpp"
#include "commands.hpp"
#include "image_io.hpp"
#include "renderer.hpp"
#include "scene_args.hpp"
#include "executor.hpp"
#include "util/atomic_file.hpp"

#include "ao_error.hpp"
#include "flicker.hpp"
#include "rt_ao.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace pathlet::cli {
namespace {

namespace fs = std::filesystem;
using quality::FrameSample;

// What the patched graph binds, or why it cannot be measured.
struct Patch {
    std::string why_not;  // non-empty: not measurable
    std::string line_id, normal_depth, ao;
};

json read_json(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot read");
    std::stringstream s;
    s << in.rdbuf();
    try {
        return json::parse(s.str(), nullptr, true, /*ignore_comments=*/true);
    } catch (const json::exception& e) {
        throw std::runtime_error(path + ": not valid JSON: " + e.what());
    }
}

// Keeps the patched resources alive to the end of the frame (outputs without capture).
void keep(json& g, const Patch& p) {
    for (const std::string& r : {p.line_id, p.normal_depth, p.ao}) g["outputs"].push_back({{"resource", r}});
}

// The OIT graph with per-fragment volume AO: resolve_list's front fragment per pixel.
Patch patch_front_layer(json& g, json& resolve) {
    Patch p;
    p.normal_depth = "quality_front_normal_depth";
    p.line_id = "quality_front_line_id";
    p.ao = "quality_front_ao";
    json& outs = resolve["outputs"];
    outs["front_normal_depth"] = p.normal_depth;
    outs["front_line_id"] = p.line_id;
    outs["front_ao"] = p.ao;
    g["resources"][p.normal_depth] = {{"format", "rgba16f"}};
    g["resources"][p.line_id] = {{"format", "r32i"}};
    g["resources"][p.ao] = {{"format", "r16f"}};
    keep(g, p);
    return p;
}

// Binds gbuffer.line_id and the AO that reaches the image, and keeps them (outputs without
// capture) so the compiler does not cull them.
Patch patch_graph(json& g) {
    Patch p;
    json* gbuffer = nullptr;
    json* bilateral = nullptr;
    json* ao_pass = nullptr;  // the screen-space (lineao) or object-space (volume_ao) AO per pixel
    for (json& pass : g["passes"]) {
        const std::string type = pass.value("type", "");
        if (type == "bilateral") bilateral = &pass;
        if ((type == "lineao" || type == "volume_ao") && !ao_pass) ao_pass = &pass;
    }
    if (!ao_pass) {
        // Every OIT fragment shaded by its own AO (resolve_list with fill_list's records): the
        // front fragment per pixel, as resolve_list's front outputs give it.
        for (json& pass : g["passes"])
            if (pass.value("type", "") == "resolve_list" && pass.contains("inputs") && pass["inputs"].contains("records"))
                return patch_front_layer(g, pass);
        return {"no AO in this graph (no lineao or volume_ao pass, no resolve_list with fill_list's records)"};
    }
    // The G-buffer is whichever line pass writes what the AO pass reads as normal_depth: gbuffer,
    // geometric_fade, fade_core or a fade of yours (every kit G-buffer pass has line_id).
    const json& lin = (*ao_pass)["inputs"];
    const std::string nd = lin.contains("normal_depth") ? lin["normal_depth"].get<std::string>() : "";
    for (json& pass : g["passes"])
        if (pass.contains("outputs") && pass["outputs"].value("normal_depth", "") == nd && !nd.empty()) gbuffer = &pass;
    if (!gbuffer) return {"no G-buffer pass feeding the AO (no line id and depth per pixel to compare frames by)"};
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
        p.ao = (*ao_pass)["outputs"]["ao"];
    }
    keep(g, p);
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
        tube.id = int(&r - lines.lines.data());
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
// own_line: the pixel's own line may occlude it (issue 13's reference). Off by default: the
// G-buffer's point lies inside its own tube wherever the line is inclined to the view (the
// kit's tube depth moves along the view direction, not the normal: 17 % of the phantom's
// pixels at t = 9 s), and every ray from there met the tube's inside.
std::vector<float> reference_ao(const Captured& c, const Camera& cam, const quality::RayTracedAo& rt, int rays,
                                float max_distance, float offset, bool own_line) {
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
            out[i] = rt.ambient(p + n * offset, n, rays, max_distance, uint32_t(i + 1), own_line ? -1 : f.line_id[i]);
        }
    return out;
}

// A per-pixel map of the frame: colour(i) (RGB) on covered pixels, light grey elsewhere.
template <class Colour>
void write_map(const std::string& path, const FrameSample& f, Colour colour) {
    Image img;
    img.width = f.width;
    img.height = f.height;
    img.channels = 4;
    img.pixels.assign(f.size() * 4, 1.0f);
    for (size_t i = 0; i < f.size(); ++i) {
        const glm::vec3 c = f.line_id[i] >= 0 ? colour(i) : glm::vec3(0.9f);
        for (int k = 0; k < 3; ++k) img.pixels[i * 4 + k] = c[k];
    }
    ensure_parent_dir(path);
    write_image(path, img);
}

// The error: white 0, red from 0.5 on.
void write_error_image(const std::string& path, const FrameSample& f, const std::vector<float>& err) {
    write_map(path, f, [&](size_t i) {
        const float e = std::min(1.0f, err[i] * 2.0f);
        return glm::vec3(1.0f, 1.0f - e, 1.0f - e);
    });
}

// An AO map as grey, 1 = white.
void write_ao_image(const std::string& path, const FrameSample& f, const std::vector<float>& ao) {
    write_map(path, f, [&](size_t i) { return glm::vec3(std::clamp(ao[i], 0.0f, 1.0f)); });
}

int run(const std::vector<std::string>& argv) {
    Args a("quality",
           "Measures AO quality (LineAO or volume AO) at a fixed camera over a time range: temporal flicker\n"
           "(mean frame-to-frame change of AO where the same line is seen at the same depth) against the\n"
           "change of the geometry and against the change of the ray-traced AO, and the error (MAE,\n"
           "correlation) against a CPU ray-traced AO (Embree, tubes of the visible pathlets, cosine-weighted\n"
           "rays, the pixel's own line left out) of the last frame, with an error image.");
    a.positional("GRAPH", "graph file or shipped graph name (default: variant1_lineao)", false)
        .option("time", "A:B:STEP", "9:9.4:0.04", "animation times (frames at A, A+STEP, ... <= B)")
        .option("size", "WxH", "320x180", "output size in pixels")
        .option("rays", "N", "256", "ray-traced AO: rays per pixel")
        .option("flicker-rays", "N", "256",
                "ray-traced AO of every frame, for the flicker against the reference's own change: rays per pixel "
                "(0: not measured)")
        .option("max-distance", "WIDTHS", "10", "ray-traced AO: ray length in line widths")
        .option("own-line", "exclude|include", "exclude",
                "ray-traced AO: whether a pixel's own line occludes it (include: issue 13's reference)")
        .option("depth-tolerance", "D", "0.002", "flicker: largest change of linear depth that counts as unchanged")
        .option("out", "DIR", "out/quality", "folder for the per-pixel error image")
        .flag("images", "also write the last frame's AO and the ray-traced AO as grey images (NAME_ao.png, "
                        "NAME_reference.png)")
        .multi("set", "NAME=VALUE", "override a graph variable or a pass parameter");
    add_scene_options(a);
    if (!a.parse(argv)) return 0;
    RenderOptions opt;
    try {
        opt.graph_path = resolve_graph_path(a.pos("GRAPH").empty() ? "variant1_lineao" : a.pos("GRAPH"));
        opt.size = parse_size(a.get("size"));
        opt.time = parse_time_range(a.get("time"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    const int rays = int(a.integer("rays")), flicker_rays = int(a.integer("flicker-rays"));
    if (rays < 1) throw UsageError("--rays must be >= 1");
    if (flicker_rays < 0) throw UsageError("--flicker-rays must be >= 0");
    const float reach = float(a.number("max-distance")), tol = float(a.number("depth-tolerance"));
    if (a.get("own-line") != "exclude" && a.get("own-line") != "include")
        throw UsageError("--own-line must be exclude or include, got '" + a.get("own-line") + "'");
    const bool own_line = a.get("own-line") == "include";
    opt.sets = a.all("set");
    opt.write_images = false;
    opt.quiet = true;
    opt.warmup = 1;

    json g = read_json(opt.graph_path);
    const std::string name = g.value("name", fs::path(opt.graph_path).stem().string());
    Patch patch = patch_graph(g);
    if (!patch.why_not.empty()) {
        std::printf("%s: not measured: %s\n", name.c_str(), patch.why_not.c_str());
        return 0;
    }
    const std::string out_dir = a.get("out");
    fs::create_directories(out_dir);
    const std::string patched = out_dir + "/." + name + ".quality.json";
    write_file_atomic(patched, g.dump(2));
    opt.graph_path = patched;

    // The patched copy is a temporary: gone however the run ends.
    struct Remove { std::string p; ~Remove() { std::error_code ec; fs::remove(p, ec); } } remove_patched{patched};
    Runtime rt;
    rt.load_plugins({});
    Scene scene = load_scene(a, true);
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
    const std::vector<float> ref = reference_ao(last, cam, tracer, rays, reach * width, 0.05f * width, own_line);
    // The reference of every frame (fewer rays: the same ones per pixel in every frame, so
    // what changes is the scene): the change it has itself is not flicker.
    quality::ReferenceFlicker rf;
    if (flicker_rays > 0) {
        std::vector<std::vector<float>> refs;
        for (const Captured& c : frames) {
            quality::RayTracedAo t(visible_tubes(scene.lines, c.time, window, 0.5f * width));
            refs.push_back(reference_ao(c, cam, t, flicker_rays, reach * width, 0.05f * width, own_line));
        }
        rf = quality::measure_flicker_against(samples, refs, tol);
    }
    const quality::AoError err = quality::measure_ao_error(last.sample, ref);
    const std::string image = out_dir + "/" + name + "_error.png";
    write_error_image(image, last.sample, err.abs_error);
    if (a.has("images")) {
        write_ao_image(out_dir + "/" + name + "_ao.png", last.sample, last.sample.ao);
        write_ao_image(out_dir + "/" + name + "_reference.png", last.sample, ref);
    }

    std::printf("%s: %zu frames %dx%d, t=%.2f..%.2f\n", name.c_str(), frames.size(), opt.size.x, opt.size.y,
                frames.front().time, last.time);
    std::printf("  flicker: mean |dAO| %.5f over %zu stable pixels; geometry change %.3f of covered pixels\n",
                fl.ao_flicker, fl.stable_pixels, fl.geometry_change);
    if (flicker_rays > 0)
        std::printf("  ray-traced AO (%d rays/px) changes by %.5f at those pixels; the AO's change beyond it, mean "
                    "|dAO - dRT|: %.5f\n",
                    flicker_rays, rf.reference_change, rf.excess);
    std::printf("  vs ray-traced AO (%d rays/px, reach %.3g = %.0f line widths, %zu tube segments): MAE %.4f, "
                "correlation %.3f over %zu px\n",
                rays, reach * width, reach, tracer.segments(), err.mae, err.correlation, err.pixels);
    std::printf("  error image: %s\n", image.c_str());
    return 0;
}

PATHLET_COMMAND("quality", "AO quality: temporal flicker and error against ray-traced AO", run);

}  // namespace
}  // namespace pathlet::cli
