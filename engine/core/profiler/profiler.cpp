// Recording side of the profiler: frame/pass boundaries and the two GPU timing backends.
#include "profiler/profiler.hpp"

#include <pathlet/gpu_fence.hpp>
#include <pathlet/pass.hpp>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <stdexcept>

namespace pathlet {

namespace {

// One rule for what is a software rasterizer: the SDK's, which impl=auto follows too.
std::string software_renderer_name(const std::string& renderer) { return software_rasterizer(renderer); }

double steady_ms() {
    using namespace std::chrono;
    return duration<double, std::milli>(steady_clock::now().time_since_epoch()).count();
}

// CPU time of every thread of the process (llvmpipe rasterizes on its own threads).
double process_cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) / 1e6;
}

}  // namespace

TimingBackend parse_timing_backend(const std::string& text) {
    if (text == "auto") return TimingBackend::Auto;
    if (text == "gpu") return TimingBackend::GlTimestamp;
    if (text == "finish") return TimingBackend::CpuFinish;
    if (text == "cpu") return TimingBackend::CpuTime;
    throw std::invalid_argument("unknown timing backend '" + text + "' (expected auto, gpu, finish or cpu)");
}

const char* to_string(TimingBackend b) {
    switch (b) {
        case TimingBackend::Auto: return "auto";
        case TimingBackend::GlTimestamp: return "gpu";
        case TimingBackend::CpuFinish: return "finish";
        case TimingBackend::CpuTime: return "cpu";
    }
    return "?";
}

bool is_software_renderer(const std::string& gl_renderer) { return !software_renderer_name(gl_renderer).empty(); }

void Profiler::init(TimingBackend requested, const std::string& gl_renderer) {
    release_gl();
    frames_.clear();
    pass_names_.clear();
    pass_depth_.clear();
    pass_ids_.clear();
    stats_.clear();
    open_passes_.clear();
    in_frame_ = false;
    frames_begun_ = 0;
    dropped_ = 0;
    warmup_seconds_ = 0;
    warmup_settled_ = true;
    wall_end_ms_ = 0;
    wall_end_frames_ = 0;

    const std::string software = software_renderer_name(gl_renderer);
    backend_ = requested;
    if (backend_ == TimingBackend::Auto)
        backend_ = software.empty() ? TimingBackend::GlTimestamp : TimingBackend::CpuFinish;

    std::string fallback;
    if (backend_ == TimingBackend::GlTimestamp) {
        GLint bits = 0;  // stays 0 without a context or without ARB_timer_query
        glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &bits);
        if (bits == 0) {
            backend_ = TimingBackend::CpuFinish;
            fallback = "GL timestamps unavailable";
        }
    }

    epoch_ms_ = clock_ ? clock_() : steady_ms();
    cpu_epoch_ms_ = process_cpu_ms();
    if (backend_ == TimingBackend::GlTimestamp) {
        description_ = "GL_TIMESTAMP queries (read when available)";
        if (!software.empty())
            description_ += " (WARNING " + software + ": timer queries do not measure rasterization)";
        // Places GPU stamps on the profiler clock, so both trace tracks share one timeline.
        GLint64 gl_now = 0;
        glGetInteger64v(GL_TIMESTAMP, &gl_now);
        gl_to_cpu_ms_ = now() - double(gl_now) / 1e6;
    } else if (backend_ == TimingBackend::CpuTime) {
        description_ = "glFinish-bracketed process CPU time (every thread's; not the wall clock";
        description_ += software.empty() ? ", and no measure of a GPU's work)" : ")";
    } else {
        description_ = "glFinish-bracketed CPU clock";
        if (!software.empty())
            description_ += " (" + software + ": timer queries do not measure rasterization)";
        else if (!fallback.empty())
            description_ += " (" + fallback + ")";
    }
}

double Profiler::now() const { return (clock_ ? clock_() : steady_ms()) - epoch_ms_; }

double Profiler::measure() const {
    return backend_ == TimingBackend::CpuTime && !clock_ ? process_cpu_ms() - cpu_epoch_ms_ : now();
}

int Profiler::pass_id(const std::string& name) {
    auto [it, added] = pass_ids_.try_emplace(name, int(pass_names_.size()));
    if (added) {
        pass_names_.push_back(name);
        pass_depth_.push_back(int(open_passes_.size()));
    }
    return it->second;
}

void Profiler::sync_point() {
    if (backend_ != TimingBackend::GlTimestamp) glFinish();
}

size_t Profiler::stamp() {
    InFlight& slot = current();
    if (slot.used == slot.queries.size()) {
        GLuint q = 0;
        glGenQueries(1, &q);
        slot.queries.push_back(q);
    }
    glQueryCounter(slot.queries[slot.used], GL_TIMESTAMP);
    return slot.used++;
}

void Profiler::begin_frame(uint64_t index) {
    if (in_frame_) throw std::logic_error("Profiler::begin_frame: frame " + std::to_string(index) +
                                         " begun before the previous one ended");
    FrameRecord f;
    f.index = index;
    f.warmup = frames_begun_ < uint64_t(warmup_frames_);
    ++frames_begun_;

    if (backend_ == TimingBackend::GlTimestamp) {
        collect_ready();
        if (in_flight_.size() >= kMaxInFlight) {  // GPU hopelessly behind: wait, never drop
            if (!said_behind_)
                std::fprintf(stderr, "profiler: the GPU's timer queries are %zu frames behind; waiting for the oldest "
                                     "(no frame is dropped)\n", in_flight_.size());
            said_behind_ = true;
            try_collect(in_flight_.front(), true);
            spare_sets_.push_back(std::move(in_flight_.front().queries));
            in_flight_.pop_front();
        }
        InFlight slot;
        if (!spare_sets_.empty()) {
            slot.queries = std::move(spare_sets_.back());
            spare_sets_.pop_back();
        }
        slot.frame = frames_.size();
        slot.issued = gpu_frame();
        in_flight_.push_back(std::move(slot));
        current().frame_begin = stamp();
    } else {
        sync_point();  // earlier work must not be billed to this frame
    }
    f.cpu.begin = now();
    f.gpu.begin = measure();
    frames_.push_back(std::move(f));
    in_frame_ = true;
}

void Profiler::end_frame() {
    if (!in_frame_) throw std::logic_error("Profiler::end_frame without begin_frame");
    if (!open_passes_.empty())
        throw std::logic_error("Profiler::end_frame: pass '" +
                               pass_names_[size_t(frames_.back().passes[open_passes_.back()].pass)] + "' still open");
    FrameRecord& f = frames_.back();
    f.cpu.end = now();
    f.cpu.valid = true;
    if (backend_ == TimingBackend::GlTimestamp) {
        current().frame_end = stamp();
        // Submits the frame (queries included) without waiting: headless there is no swap to
        // do it, and a query that is never submitted never becomes available.
        glFlush();
    } else {
        sync_point();
        f.gpu.end = measure();
        f.gpu.valid = true;
    }
    in_frame_ = false;
}

void Profiler::begin_pass(const std::string& name) {
    if (!in_frame_) throw std::logic_error("Profiler::begin_pass('" + name + "') outside a frame");
    PassSample s;
    s.pass = pass_id(name);
    s.depth = int(open_passes_.size());
    if (backend_ == TimingBackend::GlTimestamp)
        current().pass_stamps.push_back({stamp(), 0});
    else
        sync_point();
    s.cpu.begin = now();
    s.gpu.begin = measure();
    FrameRecord& f = frames_.back();
    open_passes_.push_back(f.passes.size());
    f.passes.push_back(s);
}

void Profiler::end_pass() {
    if (open_passes_.empty()) throw std::logic_error("Profiler::end_pass without begin_pass");
    size_t i = open_passes_.back();
    open_passes_.pop_back();
    PassSample& s = frames_.back().passes[i];
    s.cpu.end = now();
    s.cpu.valid = true;
    if (backend_ == TimingBackend::GlTimestamp) {
        current().pass_stamps[i][1] = stamp();
    } else {
        sync_point();
        s.gpu.end = measure();
        s.gpu.valid = true;
    }
}

void Profiler::add_stat(const std::string& pass, const std::string& name, double value) {
    if (in_frame_ && frames_.back().warmup) return;
    StatAccum& a = stats_[pass_id(pass)][name];
    a.sum += value;
    ++a.n;
}

bool Profiler::try_collect(InFlight& slot, bool wait) {
    if (!wait)
        for (size_t i = 0; i < slot.used; ++i)
            if (!query_ready(slot.queries[i], slot.issued)) return false;
    std::vector<GLuint64> ns(slot.used, 0);
    for (size_t i = 0; i < slot.used; ++i) glGetQueryObjectui64v(slot.queries[i], GL_QUERY_RESULT, &ns[i]);

    FrameRecord& f = frames_[slot.frame];
    // No GPU interval of this frame can be longer than the time from its begin_frame until
    // its results were seen; anything else (0, wrapped, garbage) is discarded.
    const double bound = now() - f.cpu.begin;
    auto interval = [&](size_t a, size_t b) {
        Interval iv;
        if (ns[a] == 0 || ns[b] == 0 || ns[b] <= ns[a]) return iv;
        double ms = double(ns[b] - ns[a]) / 1e6;
        if (ms > bound) return iv;
        iv.begin = double(ns[a]) / 1e6 + gl_to_cpu_ms_;
        iv.end = iv.begin + ms;
        iv.valid = true;
        return iv;
    };
    f.gpu = interval(slot.frame_begin, slot.frame_end);
    if (!f.gpu.valid) ++dropped_;
    for (size_t i = 0; i < slot.pass_stamps.size() && i < f.passes.size(); ++i)
        f.passes[i].gpu = interval(slot.pass_stamps[i][0], slot.pass_stamps[i][1]);
    return true;
}

void Profiler::collect_ready() {
    // GPUs finish frames in order: stop at the first one still running.
    while (!in_flight_.empty() && try_collect(in_flight_.front(), false)) {
        spare_sets_.push_back(std::move(in_flight_.front().queries));
        in_flight_.pop_front();
    }
}

size_t Profiler::frames_timed() const {
    if (!in_flight_.empty()) return in_flight_.front().frame;
    return frames_.size() - (in_frame_ ? 1 : 0);
}

void Profiler::forget_timed() {
    const size_t n = frames_timed();
    frames_.erase(frames_.begin(), frames_.begin() + long(n));
    for (InFlight& slot : in_flight_) slot.frame -= n;
    stats_.clear();
    wall_end_ms_ = 0;
    wall_end_frames_ = 0;
}

void Profiler::flush() {
    if (backend_ == TimingBackend::GlTimestamp) {
        const size_t keep = in_frame_ ? 1 : 0;  // the frame being recorded is not submitted yet
        while (in_flight_.size() > keep) {
            try_collect(in_flight_.front(), true);
            spare_sets_.push_back(std::move(in_flight_.front().queries));
            in_flight_.pop_front();
        }
    }
    // The wall clock's end: the first flush after the last frame (its GPU work is done by now).
    if (!in_frame_ && frames_.size() != wall_end_frames_) {
        wall_end_ms_ = now();
        wall_end_frames_ = frames_.size();
    }
}

double Profiler::wall_fps() const {
    const FrameRecord* first = nullptr;
    size_t n = 0;
    for (const auto& f : frames_)
        if (measured(f) && f.cpu.valid) {
            if (!first) first = &f;
            ++n;
        }
    if (!first || wall_end_frames_ == 0 || wall_end_ms_ <= first->cpu.begin) return 0.0;
    return double(n) * 1000.0 / (wall_end_ms_ - first->cpu.begin);
}

void Profiler::release_gl() {
    flush();
    for (auto& slot : in_flight_) spare_sets_.push_back(std::move(slot.queries));
    in_flight_.clear();
    for (auto& set : spare_sets_)
        if (!set.empty()) glDeleteQueries(GLsizei(set.size()), set.data());
    spare_sets_.clear();
}

}  // namespace pathlet
