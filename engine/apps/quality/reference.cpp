#include "reference.hpp"

#include "executor.hpp"
#include "graph/graph_model.hpp"
#include "image_io.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace pathlet::quality {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// What is read of a graph after every frame: its picture and its coverage.
struct Reads {
    std::string name, picture, coverage;
};

bool is_depth(const json& g, const std::string& resource) {
    if (!g.contains("resources") || !g["resources"].contains(resource)) return false;
    const std::string f = g["resources"][resource].value("format", "");
    return f == "depth24" || f == "depth32f";
}

Reads reads_of(const std::string& path) {
    const json g = expanded_graph_json(path);
    Reads r;
    r.name = g.value("name", fs::path(path).stem().string());
    if (!g.contains("outputs") || g["outputs"].empty() || !g["outputs"][0].contains("resource"))
        throw std::invalid_argument(path + ": the graph has no output to compare");
    r.picture = g["outputs"][0]["resource"].get<std::string>();
    // The depth the wall is tested against is where lines are (every OIT graph composes so) ...
    for (const json& p : g["passes"])
        if (p.value("type", "") == "aorta_backface" && p.contains("inputs") && p["inputs"].contains("depth") &&
            is_depth(g, p["inputs"]["depth"].get<std::string>()))
            r.coverage = p["inputs"]["depth"].get<std::string>();
    // ... else a line pass's depth output (coverage, depth).
    for (const json& p : g["passes"]) {
        if (!r.coverage.empty() || !p.contains("outputs")) break;
        for (const char* pin : {"coverage", "depth"})
            if (p["outputs"].contains(pin) && is_depth(g, p["outputs"][pin].get<std::string>())) {
                r.coverage = p["outputs"][pin].get<std::string>();
                break;
            }
    }
    if (r.coverage.empty())
        throw std::invalid_argument(path + ": no coverage to measure over (no depth read by an aorta_backface pass, "
                                           "no line pass with a depth24 'coverage' or 'depth' output)");
    return r;
}

struct Frames {
    std::vector<Image> pictures;
    std::vector<std::vector<uint8_t>> covered;
};

// Rendered with ssaa x ssaa samples a pixel: the picture box-filtered to the size, a pixel covered
// where any of its samples is.
Frames render_frames(Runtime& rt, const Scene& scene, const std::string& path, const Reads& reads,
                     const ReferenceOptions& o, const std::vector<std::string>& own_sets, const TimeRange& time,
                     int ssaa) {
    RenderOptions opt;
    opt.graph_path = path;
    opt.sets = o.sets;
    opt.sets.insert(opt.sets.end(), own_sets.begin(), own_sets.end());
    opt.size = o.size;
    opt.time = time;
    opt.write_images = false;
    opt.quiet = true;
    opt.warmup = 0;
    opt.ssaa = ssaa;
    opt.keep = {reads.picture, reads.coverage};
    Frames f;
    render(rt, scene, opt, [&](const Executor& ex, size_t) {
        const Texture pic = ex.texture(reads.picture), cov = ex.texture(reads.coverage);
        f.pictures.push_back(box_downsample(read_texture(pic.id, pic.width, pic.height, 0, 4), ssaa));
        std::vector<float> depth(size_t(cov.width) * size_t(cov.height));
        glGetTextureImage(cov.id, 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(depth.size() * sizeof(float)), depth.data());
        const int w = cov.width / ssaa, h = cov.height / ssaa;
        std::vector<uint8_t> mask(size_t(w) * size_t(h), 0);
        for (int y = 0; y < h * ssaa; ++y)  // GL rows bottom-up, images top-down
            for (int x = 0; x < w * ssaa; ++x)
                if (depth[size_t(cov.height - 1 - y) * size_t(cov.width) + size_t(x)] < 1.0f)
                    mask[size_t(y / ssaa) * size_t(w) + size_t(x / ssaa)] = 1;
        f.covered.push_back(std::move(mask));
    });
    return f;
}

}  // namespace

ReferenceResult measure_against_reference(Runtime& rt, const Scene& scene, const ReferenceOptions& o) {
    const Reads test = reads_of(o.graph_path), ref = reads_of(o.reference_path);
    const TimeRange time = o.time ? *o.time : default_quality_time(scene);
    if (!o.time) std::fprintf(stderr, "note: %s\n", picked_time_note(time, scene, "11 frames from the middle").c_str());
    const Frames a = render_frames(rt, scene, o.graph_path, test, o, {}, time, 1);
    // A supersampled reference's samples are the truth: its own edge anti-aliasing (the variable
    // `aa` of the shipped graphs) would blur them.
    std::vector<std::string> ref_sets = o.reference_sets;
    const json ref_graph = expanded_graph_json(o.reference_path);
    if (o.reference_ssaa > 1 && ref_graph.contains("variables") && ref_graph["variables"].contains("aa"))
        ref_sets.push_back("aa=false");
    const Frames b = render_frames(rt, scene, o.reference_path, ref, o, ref_sets, time, std::max(o.reference_ssaa, 1));
    if (a.pictures.size() != b.pictures.size() || a.pictures.empty())
        throw std::runtime_error("the graphs rendered " + std::to_string(a.pictures.size()) + " and " +
                                 std::to_string(b.pictures.size()) + " frames");
    ReferenceResult r;
    r.graph = test.name;
    r.reference = ref.name;
    r.frames = a.pictures.size();
    const std::vector<double> times = time.times();
    r.first_time = times.front();
    r.last_time = times[std::min(times.size(), r.frames) - 1];
    std::vector<std::vector<uint8_t>> either(r.frames);
    std::vector<std::vector<float>> flips(o.out_dir.empty() ? 0 : r.frames);  // kept for --out only
    for (size_t k = 0; k < r.frames; ++k) {
        either[k] = a.covered[k];
        for (size_t i = 0; i < either[k].size(); ++i) either[k][i] |= b.covered[k][i];
        r.per_frame.push_back(
            compare_images(a.pictures[k], b.pictures[k], either[k], o.ppd, flips.empty() ? nullptr : &flips[k]));
        // Pooled over the frames: squared levels and speckles weighted by each frame's covered pixels.
        const AaFigures fa = aa_figures(a.pictures[k], b.pictures[k]), fb = aa_figures(b.pictures[k], b.pictures[k]);
        r.aa.rms += fa.rms * fa.rms * double(fa.covered);
        r.aa.speckle += fa.speckle * double(fa.covered);
        r.aa.covered += fa.covered;
        r.reference_aa.speckle += fb.speckle * double(fb.covered);
        r.reference_aa.covered += fb.covered;
    }
    if (r.aa.covered) r.aa.rms = std::sqrt(r.aa.rms / double(r.aa.covered)), r.aa.speckle /= double(r.aa.covered);
    if (r.reference_aa.covered) r.reference_aa.speckle /= double(r.reference_aa.covered);
    r.metrics = pool(r.per_frame);
    if (r.frames >= 2) r.flicker = flicker_vs_reference(a.pictures, b.pictures, either);
    if (!o.out_dir.empty()) {
        fs::create_directories(o.out_dir);
        const std::string stem = o.out_dir + "/" + r.graph + "_vs_" + r.reference;
        for (size_t k = 0; k < r.frames; ++k) {
            char name[32];
            std::snprintf(name, sizeof name, "_diff_%05zu.png", k);
            r.images.push_back(stem + name);
            write_image(r.images.back(), difference_image(a.pictures[k], b.pictures[k], either[k]));
            std::snprintf(name, sizeof name, "_flip_%05zu.png", k);
            r.images.push_back(stem + name);
            write_image(r.images.back(), flip_image(flips[k], a.pictures[k].width, a.pictures[k].height, &either[k]));
        }
        r.images.push_back(o.out_dir + "/" + r.graph + "_last.png");
        write_image(r.images.back(), a.pictures.back());
        r.images.push_back(o.out_dir + "/" + r.reference + "_last.png");
        write_image(r.images.back(), b.pictures.back());
    }
    return r;
}

}  // namespace pathlet::quality
