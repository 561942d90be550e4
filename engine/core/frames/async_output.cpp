#include "frames/async_output.hpp"

#include "formats.hpp"
#include "frames/byte_readback.hpp"
#include "frames/file_complete.hpp"
#include "frames/native_readback.hpp"
#include "util/atomic_file.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <thread>

namespace fs = std::filesystem;

namespace pathlet {

namespace {

int default_threads() {
    const unsigned cores = std::thread::hardware_concurrency();
    return int(std::clamp(cores, 1u, 4u));
}

bool is_depth(GLenum f) {
    // read_texture's list: these read as GL_DEPTH_COMPONENT and spread to grey.
    return f == GL_DEPTH_COMPONENT16 || f == GL_DEPTH_COMPONENT24 || f == GL_DEPTH_COMPONENT32F ||
           f == GL_DEPTH_COMPONENT32;
}

// A colour format texelFetch can read as floats (the GPU filter's candidates).
bool is_filterable(GLenum f) {
    const FormatInfo* fi = find_format(f);
    return fi && !fi->depth && !fi->is_integer;
}

}  // namespace

AsyncOutput::AsyncOutput(Options o)
    : opt_(std::move(o)),
      jobs_(opt_.threads > 0 ? opt_.threads : default_threads(),
            opt_.max_queued > 0 ? opt_.max_queued : size_t(opt_.threads > 0 ? opt_.threads : default_threads()) + 2),
      ring_(opt_.ring_depth) {
    opt_.ssaa = std::max(1, opt_.ssaa);
}

AsyncOutput::~AsyncOutput() {
    jobs_.abandon();  // cancelled jobs remove their files; nothing runs after this
    for (const auto& [dir, tmp] : staging_) discard_temp(tmp);
}

AsyncOutput::Plan AsyncOutput::plan_for(const Capture& c) {
    const GLenum f = c.tex.internal_format;
    const FormatInfo* fi = find_format(f);
    // Asked here, not of GL after the copy: a glGetError a frame is a round trip to a threaded driver.
    if (fi && (fi->is_integer || (fi->depth && !is_depth(f))))
        throw std::runtime_error(c.what + ": cannot read the texture back: " + fi->name +
                                 " is not a colour or depth format an image holds");
    const int factor = c.factor > 0 ? c.factor : opt_.ssaa;
    Plan p;
    if (is_depth(f)) {
        p.layout = RawFrame::Layout::Depth;
        p.factor = factor;
        p.format = GL_DEPTH_COMPONENT;
        if (depth_copy_.exact(f)) p.depth_copy = true, p.format = GL_RED;  // R32F on the GPU
        return p;
    }
    NativeRead native;
    const bool own_format = native_read(f, native) && widening_exact(f);
    if (factor > 1) {
        p.factor = factor;
        if (is_filterable(f) && filter_.exact(f, factor)) {
            p.layout = RawFrame::Layout::Sums;
            return p;
        }
        // The full size read back, the CPU filters it on a writer.
        if (!opt_.quiet && !noted_cpu_filter_ && is_filterable(f)) {
            std::fprintf(stderr, "note: %s (%s): supersampling resolved on the CPU (this driver's GPU filter differs from it)\n",
                         c.what.c_str(), fi ? fi->name : "?");
            noted_cpu_filter_ = true;
        }
    } else {
        auto it = tables_.find(f);
        if (it == tables_.end()) it = tables_.emplace(f, measure_byte_table(f)).first;
        if (it->second) {
            p.layout = RawFrame::Layout::Bytes;
            p.table = it->second;
            p.type = GL_UNSIGNED_BYTE;
            return p;
        }
    }
    if (own_format) {  // r16f: 2 bytes a pixel, widened on a writer
        p.format = native.format;
        p.type = native.type;
        p.channels = native.channels;
        p.half = native.half;
    }
    return p;
}

std::string AsyncOutput::staging_dir(const std::string& file) {
    const fs::path parent = fs::path(file).parent_path();
    const std::string dir = parent.empty() ? std::string(".") : parent.string();
    auto it = staging_.find(dir);
    if (it == staging_.end()) it = staging_.emplace(dir, temp_dir_in(dir, "pathlet-frames")).first;
    return it->second;
}

void AsyncOutput::capture(const std::vector<Capture>& captures) {
    if (captures.empty()) return;  // nothing uses this frame's pixels: no read-back at all
    ++frames_captured_;
    for (size_t i = 0; i < captures.size(); ++i) {
        const Capture& c = captures[i];
        const std::pair<GLenum, int> key{c.tex.internal_format, c.factor > 0 ? c.factor : opt_.ssaa};
        auto pit = plans_.find(key);  // measured once per format and factor
        if (pit == plans_.end()) pit = plans_.emplace(key, plan_for(c)).first;
        const Plan& p = pit->second;
        RawFrame raw;  // all but the bytes, which the ring hands over
        raw.layout = p.layout;
        raw.factor = p.factor;
        raw.table = p.table;
        raw.channels = p.channels;
        raw.half = p.half;
        raw.width = c.tex.width;
        raw.height = c.tex.height;
        GLuint src = c.tex.id;
        if (p.layout == RawFrame::Layout::Sums) {
            raw.width /= p.factor;
            raw.height /= p.factor;
            src = filter_.sums(c.tex.id, raw.width, raw.height, p.factor, i);
        } else if (p.depth_copy) {
            src = depth_copy_.to_float(c.tex.id, c.tex.internal_format, raw.width, raw.height, i);
        }
        const bool last = i + 1 == captures.size();
        const int w = raw.width, h = raw.height, bpp = raw.bytes_per_pixel();
        ring_.copy(src, w, h, p.format, p.type, bpp,
                   [this, c, raw = std::move(raw), last](PackedPixels&& data) mutable {
                       raw.data = std::move(data);
                       submit(std::move(raw), c, last);
                   },
                   c.what);
    }
    ring_.end_frame();  // waits for the oldest frame only when the ring is full
}

void AsyncOutput::poll() { ring_.poll(); }

void AsyncOutput::finish() {
    ring_.drain();
    jobs_.finish();
    for (const auto& [dir, tmp] : staging_) discard_temp(tmp);
    staging_.clear();
}

void AsyncOutput::submit(RawFrame&& raw, const Capture& c, bool last_of_frame) {
    struct State {
        RawFrame raw;
        Image img;
        std::string file, staged;
        bool to_image = false, last = false;
        std::function<void(const Image&)> sink;
    };
    auto s = std::make_shared<State>();
    s->raw = std::move(raw);
    s->file = c.file;
    s->to_image = c.to_image && opt_.on_image;
    s->last = last_of_frame;
    s->sink = c.sink;
    if (!c.file.empty())  // numbered: a pattern without {frame} names every frame's file alike
        s->staged = (fs::path(staging_dir(c.file)) /
                     (std::to_string(job_seq_++) + "-" + fs::path(c.file).filename().string()))
                        .string();
    OrderedJobs::Job job;
    job.work = [s] {
        s->img = to_image(std::move(s->raw));
        if (s->staged.empty()) return;
        try {
            write_image(s->staged, s->img);
        } catch (const std::runtime_error& e) {  // named by the file the user asked for
            std::string m = e.what();
            if (m.compare(0, s->staged.size(), s->staged) == 0) m = s->file + m.substr(s->staged.size());
            throw std::runtime_error(m);
        }
        if (!image_file_complete(s->staged))  // a full disk cuts files short without the encoder noticing
            throw std::runtime_error(s->file + ": cannot write image: the file came out incomplete (is the disk full?)");
        if (!s->to_image && !s->sink) s->img = {};  // encoded: the pixels are not needed while it waits its turn
    };
    job.commit = [this, s] {
        if (!s->staged.empty()) commit_temp(s->staged, s->file);
        if (s->to_image) opt_.on_image(s->img);
        if (s->sink) s->sink(s->img);
        if (s->last) ++frames_written_;
    };
    job.cancel = [s] {
        std::error_code ec;
        if (!s->staged.empty()) fs::remove(s->staged, ec);
    };
    jobs_.submit(std::move(job));
}

}  // namespace pathlet
