#include "reference.hpp"

#include "executor.hpp"
#include "graph/graph_model.hpp"
#include "image_io.hpp"

#include <nlohmann/json.hpp>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
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
    r.name = parse_graph_file(path).name;  // checked: it names files in --out
    if (!g.contains("outputs") || g["outputs"].empty() || !g["outputs"][0].contains("resource"))
        throw std::invalid_argument(path + ": the graph has no output to compare");
    r.picture = g["outputs"][0]["resource"].get<std::string>();
    // The depth the wall is tested against is where lines are (every OIT graph composes so) ...
    for (const json& p : g["passes"])
        if (p.value("type", "") == "aorta_backface" && p.contains("inputs") && p["inputs"].contains("depth") &&
            is_depth(g, p["inputs"]["depth"].get<std::string>()))
            r.coverage = p["inputs"]["depth"].get<std::string>();
    // ... else the first line pass's depth output (coverage, depth); passes without outputs are
    // passed over.
    for (const json& p : g["passes"]) {
        if (!r.coverage.empty()) break;
        if (!p.contains("outputs")) continue;
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

// One frame of a graph: its picture and where it covers.
struct Sample {
    Image picture;
    std::vector<uint8_t> covered;
    bool bytes = false;  // the picture is 8-bit (stored and compared as its levels)
};

// Rendered with ssaa x ssaa samples a pixel: the picture box-filtered to the size, a pixel covered
// where any of its samples is.
Sample read_sample(const Executor& ex, const Reads& reads, int ssaa) {
    const Texture pic = ex.texture(reads.picture), cov = ex.texture(reads.coverage);
    Sample s;
    s.picture = read_texture(pic.id, pic.width, pic.height, 0, 4);
    // An 8-bit picture's values are its levels: both graphs' frames go through the same rule,
    // so a frame kept as bytes compares as if it had never left the GPU.
    s.bytes = pic.internal_format == GL_RGBA8 || pic.internal_format == GL_SRGB8_ALPHA8;
    if (s.bytes)
        for (float& v : s.picture.pixels) v = float(to_unorm8(v)) / 255.0f;
    if (ssaa > 1) {
        s.picture = box_downsample(s.picture, ssaa);
        s.bytes = false;  // an average of levels
    }
    std::vector<float> depth(size_t(cov.width) * size_t(cov.height));
    glGetTextureImage(cov.id, 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(depth.size() * sizeof(float)), depth.data());
    const int w = cov.width / ssaa, h = cov.height / ssaa;
    s.covered.assign(size_t(w) * size_t(h), 0);
    for (int y = 0; y < h * ssaa; ++y)  // GL rows bottom-up, images top-down
        for (int x = 0; x < w * ssaa; ++x)
            if (depth[size_t(cov.height - 1 - y) * size_t(cov.width) + size_t(x)] < 1.0f)
                s.covered[size_t(y / ssaa) * size_t(w) + size_t(x / ssaa)] = 1;
    return s;
}

// The frames of the graph under test, kept compressed in an unnamed temporary file while the
// reference renders, then read back one at a time in order: memory holds a frame or two
// however many frames are compared (1080p is 33 MB a frame as floats).
class Spool {
public:
    Spool() : file_(std::tmpfile(), &std::fclose) {
        if (!file_) throw std::runtime_error("quality --reference: cannot make a temporary file for the frames");
    }
    void put(const Sample& s) {
        std::vector<uint8_t> raw;
        if (s.bytes) {
            raw.resize(s.picture.pixels.size());
            for (size_t i = 0; i < raw.size(); ++i) raw[i] = to_unorm8(s.picture.pixels[i]);
        } else {
            raw.resize(s.picture.pixels.size() * sizeof(float));
            std::memcpy(raw.data(), s.picture.pixels.data(), raw.size());
        }
        raw.insert(raw.end(), s.covered.begin(), s.covered.end());
        uLongf packed_size = compressBound(uLong(raw.size()));
        std::vector<uint8_t> packed(packed_size);
        if (compress2(packed.data(), &packed_size, raw.data(), uLong(raw.size()), 1) != Z_OK)
            throw std::runtime_error("quality --reference: cannot compress a frame");
        const uint64_t head[5] = {uint64_t(s.picture.width), uint64_t(s.picture.height), uint64_t(s.bytes),
                                  uint64_t(raw.size()), uint64_t(packed_size)};
        if (std::fwrite(head, sizeof head, 1, file_.get()) != 1 ||
            std::fwrite(packed.data(), 1, packed_size, file_.get()) != packed_size)
            throw std::runtime_error("quality --reference: cannot write a frame to the temporary file (disk full?)");
        ++frames_;
    }
    size_t frames() const { return frames_; }
    void rewind() { std::rewind(file_.get()); }
    Sample next() {
        uint64_t head[5];
        if (std::fread(head, sizeof head, 1, file_.get()) != 1) throw std::runtime_error("quality --reference: frame missing");
        std::vector<uint8_t> packed(head[4]), raw(head[3]);
        uLongf raw_size = uLongf(head[3]);
        if (std::fread(packed.data(), 1, packed.size(), file_.get()) != packed.size() ||
            uncompress(raw.data(), &raw_size, packed.data(), uLong(packed.size())) != Z_OK || raw_size != head[3])
            throw std::runtime_error("quality --reference: a frame in the temporary file is unreadable");
        Sample s;
        s.picture.width = int(head[0]);
        s.picture.height = int(head[1]);
        s.bytes = head[2] != 0;
        const size_t values = size_t(head[0]) * size_t(head[1]) * 4, pixels = values / 4;
        s.picture.pixels.resize(values);
        if (s.bytes)
            for (size_t i = 0; i < values; ++i) s.picture.pixels[i] = float(raw[i]) / 255.0f;
        else
            std::memcpy(s.picture.pixels.data(), raw.data(), values * sizeof(float));
        const size_t at = s.bytes ? values : values * sizeof(float);
        s.covered.assign(raw.begin() + long(at), raw.begin() + long(at + pixels));
        return s;
    }

private:
    std::unique_ptr<FILE, int (*)(FILE*)> file_;
    size_t frames_ = 0;
};

RenderResult render_graph(Runtime& rt, const Scene& scene, const std::string& path, const Reads& reads,
                          const ReferenceOptions& o, const std::vector<std::string>& own_sets, const TimeRange& time,
                          int ssaa, const std::function<void(Sample&&)>& take) {
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
    return render(rt, scene, opt, [&](const Executor& ex, size_t) { take(read_sample(ex, reads, ssaa)); });
}

// "3, 4 and 11 of 11"
std::string frame_list(const std::vector<size_t>& frames, size_t of) {
    std::string s;
    for (size_t i = 0; i < frames.size(); ++i)
        s += (i ? (i + 1 == frames.size() ? " and " : ", ") : "") + std::to_string(frames[i]);
    return s + " of " + std::to_string(of);
}

}  // namespace

ReferenceResult measure_against_reference(Runtime& rt, const Scene& scene, const ReferenceOptions& o) {
    const Reads test = reads_of(o.graph_path), ref = reads_of(o.reference_path);
    const TimeRange time = o.time ? *o.time : default_quality_time(scene);
    if (!o.time) std::fprintf(stderr, "note: %s\n", picked_time_note(time, scene, "11 frames from the middle").c_str());
    ReferenceResult r;
    r.graph = test.name;
    r.reference = ref.name;
    Spool spool;
    const RenderResult tested = render_graph(rt, scene, o.graph_path, test, o, {}, time, 1, [&](Sample&& s) { spool.put(s); });
    r.incomplete_frames = tested.incomplete_frames;
    spool.rewind();
    const std::string stem = o.out_dir + "/" + r.graph + "_vs_" + r.reference;
    if (!o.out_dir.empty()) fs::create_directories(o.out_dir);
    // Each reference frame is measured as it arrives, against the test's frame of that time.
    // A supersampled reference's samples are the truth: its own edge anti-aliasing (the variable
    // `aa` of the shipped graphs) would blur them.
    std::vector<std::string> ref_sets = o.reference_sets;
    const json ref_graph = expanded_graph_json(o.reference_path);
    if (o.reference_ssaa > 1 && ref_graph.contains("variables") && ref_graph["variables"].contains("aa"))
        ref_sets.push_back("aa=false");
    FlickerAccumulator flicker;
    Sample last_test, last_ref;
    std::vector<uint8_t> last_either;
    size_t k = 0;
    const RenderResult reference = render_graph(rt, scene, o.reference_path, ref, o, ref_sets, time, std::max(o.reference_ssaa, 1), [&](Sample&& b) {
        if (k >= spool.frames())
            throw std::runtime_error("the reference rendered more frames than " + r.graph + " (" +
                                     std::to_string(spool.frames()) + ")");
        Sample a = spool.next();
        std::vector<uint8_t> either = a.covered;
        for (size_t i = 0; i < either.size() && i < b.covered.size(); ++i) either[i] |= b.covered[i];
        std::vector<float> flip;
        r.per_frame.push_back(compare_images(a.picture, b.picture, either, o.ppd, o.out_dir.empty() ? nullptr : &flip));
        // Pooled over the frames: squared levels and speckles weighted by each frame's covered pixels.
        const AaFigures fa = aa_figures(a.picture, b.picture), fb = aa_figures(b.picture, b.picture);
        r.aa.rms += fa.rms * fa.rms * double(fa.covered);
        r.aa.speckle += fa.speckle * double(fa.covered);
        r.aa.covered += fa.covered;
        r.reference_aa.speckle += fb.speckle * double(fb.covered);
        r.reference_aa.covered += fb.covered;
        if (k > 0) flicker.add(last_test.picture, a.picture, last_ref.picture, b.picture, last_either, either);
        if (!o.out_dir.empty()) {
            char name[32];
            std::snprintf(name, sizeof name, "_diff_%05zu.png", k);
            r.images.push_back(stem + name);
            write_image(r.images.back(), difference_image(a.picture, b.picture, either));
            std::snprintf(name, sizeof name, "_flip_%05zu.png", k);
            r.images.push_back(stem + name);
            write_image(r.images.back(), flip_image(flip, a.picture.width, a.picture.height, &either));
        }
        last_test = std::move(a);
        last_ref = std::move(b);
        last_either = std::move(either);
        ++k;
    });
    // A reference that lost fragments (lists that overflowed, a walk cut short) is no reference.
    if (!reference.incomplete_frames.empty())
        throw std::runtime_error("the reference " + r.reference + " rendered incomplete frames (" +
                                 frame_list(reference.incomplete_frames, reference.frames) +
                                 "): it lost fragments there, so nothing is measured against it");
    r.frames = k;
    if (r.frames != spool.frames() || r.frames == 0)
        throw std::runtime_error("the graphs rendered " + std::to_string(spool.frames()) + " and " +
                                 std::to_string(r.frames) + " frames");
    const std::vector<double> times = time.times();
    r.first_time = times.front();
    r.last_time = times[std::min(times.size(), r.frames) - 1];
    if (r.aa.covered) r.aa.rms = std::sqrt(r.aa.rms / double(r.aa.covered)), r.aa.speckle /= double(r.aa.covered);
    if (r.reference_aa.covered) r.reference_aa.speckle /= double(r.reference_aa.covered);
    r.metrics = pool(r.per_frame);
    if (r.frames >= 2) r.flicker = flicker.result();
    if (!o.out_dir.empty()) {
        r.images.push_back(o.out_dir + "/" + r.graph + "_last.png");
        write_image(r.images.back(), last_test.picture);
        r.images.push_back(o.out_dir + "/" + r.reference + "_last.png");
        write_image(r.images.back(), last_ref.picture);
    }
    return r;
}

std::string incomplete_frames_note(const ReferenceResult& r) {
    if (r.incomplete_frames.empty()) return "";
    return r.graph + " rendered incomplete frames (" + frame_list(r.incomplete_frames, r.frames) +
           "): it lost fragments there, and the measures include them";
}

}  // namespace pathlet::quality
