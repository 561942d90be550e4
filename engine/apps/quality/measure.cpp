#include "measure.hpp"

#include "rt_ao.hpp"

#include "executor.hpp"
#include "graph/graph_model.hpp"
#include "util/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace pathlet::quality {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// What the patched graph binds, or why it cannot be measured.
struct Patch {
    std::string why_not;  // non-empty: not measurable
    std::string line_id, normal_depth, ao;
};

Patch not_measurable(const std::string& why) {
    Patch p;
    p.why_not = why;
    return p;
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

// Binds the G-buffer's line_id and the AO that reaches the image, and keeps them (outputs
// without capture) so the compiler does not cull them.
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
        return not_measurable("no AO in this graph (no lineao or volume_ao pass, no resolve_list with fill_list's records)");
    }
    // The G-buffer is whichever line pass writes what the AO pass reads as normal_depth: gbuffer,
    // geometric_fade, fade_core or a fade of yours (every kit G-buffer pass has line_id).
    const json& lin = (*ao_pass)["inputs"];
    const std::string nd = lin.contains("normal_depth") ? lin["normal_depth"].get<std::string>() : "";
    for (json& pass : g["passes"])
        if (pass.contains("outputs") && pass["outputs"].value("normal_depth", "") == nd && !nd.empty()) gbuffer = &pass;
    if (!gbuffer) return not_measurable("no G-buffer pass feeding the AO (no line id and depth per pixel to compare frames by)");
    json& outs = (*gbuffer)["outputs"];
    if (!outs.contains("normal_depth")) return not_measurable("gbuffer's normal_depth is not bound");
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

// Tubes of the visible pathlets at time t: each line clipped to [t - window, t] in time as the
// line kit clips its quads (a segment the window's end cuts is cut there, interpolated), so the
// tubes are the lines the picture draws, not up to a data segment shorter at each end.
std::vector<Tube> visible_tubes(const Pathlines& lines, double t, double window, float radius) {
    std::vector<Tube> tubes;
    const double t0 = t - window;
    for (const LineRange& r : lines.lines) {
        Tube tube;
        tube.radius = radius;
        tube.id = int(&r - lines.lines.data());
        if (window <= 0) {
            for (uint32_t i = r.first; i < r.first + r.count; ++i) tube.points.push_back(lines.position[i]);
        } else {
            for (uint32_t i = r.first; i + 1 < r.first + r.count; ++i) {
                const double ta = lines.time[i], tb = lines.time[i + 1];
                if (tb < t0 || ta > t) continue;
                const double dt = tb - ta;
                const float fa = dt > 1e-9 ? float(std::clamp((t0 - ta) / dt, 0.0, 1.0)) : 0.0f;
                const float fb = dt > 1e-9 ? float(std::clamp((t - ta) / dt, 0.0, 1.0)) : 1.0f;
                const glm::vec3 a = glm::mix(lines.position[i], lines.position[i + 1], fa);
                if (tube.points.empty() || tube.points.back() != a) tube.points.push_back(a);
                tube.points.push_back(glm::mix(lines.position[i], lines.position[i + 1], fb));
            }
        }
        if (tube.points.size() >= 2) tubes.push_back(std::move(tube));
    }
    return tubes;
}

// Ray-traced AO per covered pixel. Its point and normal: where the pixel's ray meets the pixel's
// own line's round tube (QualityOptions::gbuffer_point false), or from the G-buffer: the linear
// depth through the camera (exact inverse of engine/lines/shaders/line_common.glsl) and the
// normal; a ray that misses its tube (a rim pixel the level of detail moved) takes the G-buffer's.
// own_line: whether the pixel's own line may occlude it (QualityOptions::own_line).
std::vector<float> reference_ao(const Captured& c, const Camera& cam, const RayTracedAo& rt, int rays,
                                float max_distance, float offset, const QualityOptions& q) {
    const FrameSample& f = c.sample;
    std::vector<float> out(f.size(), 1.0f);
    const glm::mat4 inv_view = glm::inverse(cam.view);
    const glm::vec3 eye_at = glm::vec3(inv_view[3]);
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const size_t i = size_t(y) * f.width + x;
            if (f.line_id[i] < 0) continue;
            const float nx = (x + 0.5f) / f.width * 2 - 1, ny = 1 - (y + 0.5f) / f.height * 2;  // top row first
            const float eye = cam.near_plane + f.depth[i] * (cam.far_plane - cam.near_plane);
            const glm::vec4 view(nx * eye / cam.proj[0][0], ny * eye / cam.proj[1][1], -eye, 1.0f);
            glm::vec3 p = glm::vec3(inv_view * view);
            glm::vec3 n = glm::normalize(glm::mat3(inv_view) * c.normal[i]);
            if (!q.gbuffer_point) {
                glm::vec3 tube_p, tube_n;
                if (rt.surface_of(f.line_id[i], eye_at, glm::normalize(p - eye_at), tube_p, tube_n)) {
                    p = tube_p;
                    n = tube_n;
                }
            }
            out[i] = rt.ambient(p + n * offset, n, rays, max_distance, uint32_t(i + 1), q.own_line ? -1 : f.line_id[i]);
        }
    return out;
}

}  // namespace

namespace {
// A per-pixel map of the frame: colour(i) (RGB) on covered pixels, light grey elsewhere.
template <class Colour>
Image map_image(const FrameSample& f, Colour colour) {
    Image img;
    img.width = f.width;
    img.height = f.height;
    img.channels = 4;
    img.pixels.assign(f.size() * 4, 1.0f);
    for (size_t i = 0; i < f.size(); ++i) {
        const glm::vec3 c = f.line_id[i] >= 0 ? colour(i) : glm::vec3(0.9f);
        for (int k = 0; k < 3; ++k) img.pixels[i * 4 + k] = c[k];
    }
    return img;
}
}  // namespace

Image error_image(const FrameSample& f, const std::vector<float>& err) {
    return map_image(f, [&](size_t i) {
        const float e = std::min(1.0f, err[i] * 2.0f);  // 0.5 error = full red
        return glm::vec3(1.0f, 1.0f - e, 1.0f - e);
    });
}

Image ao_image(const FrameSample& f, const std::vector<float>& ao) {
    return map_image(f, [&](size_t i) { return glm::vec3(std::clamp(ao[i], 0.0f, 1.0f)); });
}

namespace {

// The graph that runs: one that extends the user's file with what patch_graph changed, so
// hook files and plugin folders next to the user's graph are still found from the work folder.
json patch_document(const std::string& graph_path, const json& full, const json& patched) {
    json doc = {{"extends", fs::absolute(graph_path).lexically_normal().string()},
                {"passes", json::array()},
                {"resources", json::object()},
                {"outputs", patched["outputs"]}};
    for (const json& p : patched["passes"]) {
        const auto same = std::find_if(full["passes"].begin(), full["passes"].end(),
                                       [&](const json& b) { return b.value("name", "") == p.value("name", ""); });
        if (same == full["passes"].end() || (*same).value("outputs", json()) != p.value("outputs", json()))
            doc["passes"].push_back({{"name", p["name"]}, {"outputs", p["outputs"]}});
    }
    for (const auto& [name, r] : patched["resources"].items())
        if (!full.contains("resources") || !full["resources"].contains(name)) doc["resources"][name] = r;
    return doc;
}

}  // namespace

void check_quality_options(const QualityOptions& q) {
    RayTracedAo::require();  // before any work, in a build without Embree
    if (q.rays < 1) throw std::invalid_argument("rays must be >= 1 (got " + std::to_string(q.rays) + ")");
    if (q.flicker_rays < 0) throw std::invalid_argument("flicker rays must be >= 0 (got " + std::to_string(q.flicker_rays) + ")");
    if (q.time && q.time->times().size() < 2) throw std::invalid_argument("time must give at least two frames (A:B:STEP)");
}

QualityResult measure_quality(Runtime& rt, const Scene& scene, const QualityOptions& q) {
    QualityResult res;
    // The graph as one document (its "extends" chain merged in) is what the patch looks at.
    const json full = expanded_graph_json(q.graph_path);
    res.graph = full.value("name", fs::path(q.graph_path).stem().string());
    json g = full;
    Patch patch = patch_graph(g);
    if (!patch.why_not.empty()) {
        res.not_measured = patch.why_not;
        return res;
    }
    RenderOptions opt;
    opt.time = q.time ? *q.time : default_quality_time(scene);
    if (!q.time) std::fprintf(stderr, "note: %s\n", picked_time_note(opt.time, scene, "11 frames from the middle").c_str());
    if (opt.time.times().size() < 2) throw std::invalid_argument("--time must give at least two frames");
    opt.size = q.size;
    opt.sets = q.sets;
    opt.write_images = false;
    opt.quiet = true;
    opt.warmup = 1;
    fs::create_directories(q.work_dir);
    // A dot file in the work folder, gone however the run ends.
    opt.graph_path = (fs::path(q.work_dir) / ("." + res.graph + ".quality.json")).string();
    write_file_atomic(opt.graph_path, patch_document(q.graph_path, full, g).dump(2));
    struct Remove {
        std::string p;
        ~Remove() {
            std::error_code ec;
            fs::remove(p, ec);
        }
    } remove_patched{opt.graph_path};

    std::vector<Captured> frames;
    const std::vector<double> times = opt.time.times();
    RenderResult rendered = render(rt, scene, opt, [&](const Executor& ex, size_t frame) {
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

    std::vector<FrameSample> samples;
    for (const Captured& c : frames) samples.push_back(c.sample);
    res.flicker = measure_flicker(samples, q.depth_tolerance);

    const json& vars = rendered.compiled.variables;
    const double window = vars.contains("window") ? vars["window"].get<double>() : 1.0;
    float width = vars.contains("line_width") ? vars["line_width"].get<float>() : 0.0f;
    const float factor = vars.contains("width_factor") ? vars["width_factor"].get<float>() : 1.0f;
    // The renderer's rule: the auto width of the whole scene's box (lines and wall), times the factor.
    if (width <= 0) width = factor * GpuScene::auto_line_width(scene.bounds());
    const Captured& last = frames.back();
    const Camera cam = frame_bounds(scene.bounds(), opt.size);
    RayTracedAo tracer(visible_tubes(scene.lines, last.time, window, 0.5f * width));
    res.reach = q.max_distance * width;
    res.segments = tracer.segments();
    res.reference = reference_ao(last, cam, tracer, q.rays, res.reach, 0.05f * width, q);
    // The reference of every frame (fewer rays: the same ones per pixel in every frame, so
    // what changes is the scene): the change it has itself is not flicker.
    if (q.flicker_rays > 0) {
        std::vector<std::vector<float>> refs;
        for (const Captured& c : frames) {
            RayTracedAo t(visible_tubes(scene.lines, c.time, window, 0.5f * width));
            refs.push_back(reference_ao(c, cam, t, q.flicker_rays, res.reach, 0.05f * width, q));
        }
        res.reference_flicker = measure_flicker_against(samples, refs, q.depth_tolerance);
    }
    res.error = measure_ao_error(last.sample, res.reference);
    res.frames = frames.size();
    res.first_time = frames.front().time;
    res.last_time = last.time;
    res.last = last.sample;
    return res;
}

}  // namespace pathlet::quality
