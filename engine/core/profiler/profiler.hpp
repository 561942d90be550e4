// Per-pass frame profiler. Two ways to time GPU work:
//  * GlTimestamp: glQueryCounter(GL_TIMESTAMP) at every boundary, a ring of in-flight frames,
//    results read only once available (pathlet/gpu_fence.hpp's query_ready: never stalls, and
//    late under PATHLET_SIMULATE_GPU_LATENCY). No frame is dropped. Right for real GPUs.
//  * CpuFinish: glFinish() then the steady clock at every boundary. Serialises the pipeline,
//    but it is the only honest number on llvmpipe, whose timer queries miss rasterisation.
//  * CpuTime: glFinish() then the process's CPU time (every thread's) at every boundary: what
//    llvmpipe's work costs, whatever else a busy machine runs (a pass's wall clock there grows
//    with the load). Says nothing of a GPU's work. scripts/perf-ab.sh times llvmpipe with it.
// CPU-side (command recording) time per pass is recorded either way, without any finish.
#pragma once

#include <pathlet/gl.hpp>

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace pathlet {

enum class TimingBackend { Auto, GlTimestamp, CpuFinish, CpuTime };

// "auto" | "gpu" | "finish" | "cpu"; throws std::invalid_argument naming the accepted words.
TimingBackend parse_timing_backend(const std::string& text);
const char* to_string(TimingBackend b);  // "auto" | "gpu" | "finish" | "cpu"

// True for renderers whose timer queries cannot be trusted (llvmpipe, softpipe, SwiftShader).
bool is_software_renderer(const std::string& gl_renderer);

class Profiler {
public:
    struct Stats {
        double median = 0, p5 = 0, p95 = 0, mean = 0, min = 0, max = 0;
        size_t n = 0;
    };
    struct PassResult {
        std::string name;
        Stats gpu_ms;  // backend-measured (timestamps or finish-bracketed)
        Stats cpu_ms;  // recording cost on the CPU, no finish
        std::map<std::string, double> stats;  // add_stat values, mean over measured frames
    };

    // Auto picks CpuFinish for software renderers, else GlTimestamp. GlTimestamp needs a
    // current context; without timestamp support it falls back to CpuFinish and says so.
    void init(TimingBackend requested, const std::string& gl_renderer);
    TimingBackend backend() const { return backend_; }
    std::string backend_description() const { return description_; }

    void set_warmup_frames(int n) { warmup_frames_ = n < 0 ? 0 : n; }  // default 3
    // Every frame begun so far was warm-up (a warm-up by time, whose length is known only after):
    // measuring starts with the next frame. `seconds` and `settled` are reported with the timing.
    void end_warmup(double seconds, bool settled) {
        warmup_frames_ = int(frames_begun_);
        warmup_seconds_ = seconds;
        warmup_settled_ = settled;
    }
    // Replaces the steady clock (milliseconds, any epoch); for deterministic tests.
    void set_clock(std::function<double()> now_ms) { clock_ = std::move(now_ms); }

    void begin_frame(uint64_t index);
    void end_frame();
    void begin_pass(const std::string& name);  // passes may nest; each is timed on its own
    void end_pass();
    // A per-pass figure such as segments drawn. Ignored during warm-up frames.
    void add_stat(const std::string& pass, const std::string& name, double value);

    // Collects GPU results of frames still in flight, waiting for them (GlTimestamp only).
    void flush();
    // Collects the GPU results that are ready, never waiting (the viewer's live timing).
    void collect_ready();
    // Frames recorded whose GPU results are in (all of them with CpuFinish).
    size_t frames_timed() const;
    // Forgets the frames whose results are in (their records and the stats); frames still in
    // flight keep their queries and are collected later. The viewer's window of recent frames.
    void forget_timed();
    // flush() and delete the query objects; the context must still be current.
    void release_gl();

    // Reports. Call flush() first when using GlTimestamp, or the last frames are missing.
    std::vector<PassResult> passes() const;  // first-seen order
    Stats frame_ms() const;                  // whole frame, backend-measured
    Stats frame_cpu_ms() const;              // whole frame, CPU wall clock
    size_t frames_recorded() const { return frames_.size(); }
    size_t gpu_frames_dropped() const { return dropped_; }  // implausible values (never for being behind)
    // Frames per second of wall clock over the measured frames: from the first one's start on the
    // CPU to the moment flush() saw the last one done (on the GPU too). What a user waits for;
    // with a CPU-bound loop far below 1000 / median frame time. 0 before flush().
    double wall_fps() const;
    // A run whose frame times spread more than kUnstableRatio (p95 / p5): the clock changed under
    // it (a GPU's governor), or something else ran. Its median is not a number to quote alone.
    static constexpr double kUnstableRatio = 1.5;
    static bool unstable(const Stats& frame) { return frame.p5 > 0 && frame.p95 / frame.p5 > kUnstableRatio; }
    bool unstable() const { return unstable(frame_ms()); }

    std::string table(const std::string& title) const;
    std::string csv() const;
    nlohmann::json to_json(const nlohmann::json& meta) const;
    nlohmann::json chrome_trace() const;  // Trace Event Format, opens in Perfetto

    // Timestamps are milliseconds since init() on the profiler's (CPU) clock.
    struct Interval {
        double begin = 0, end = 0;
        bool valid = false;
        double duration() const { return end - begin; }
    };
    struct PassSample {
        int pass = 0;  // index into pass_names_
        int depth = 0;
        Interval cpu, gpu;
    };
    struct FrameRecord {
        uint64_t index = 0;
        bool warmup = false;
        Interval cpu, gpu;
        std::vector<PassSample> passes;
    };
    // Raw per-frame records (warm-up included, marked) for reports listing every frame.
    const std::vector<FrameRecord>& frames() const { return frames_; }
    const std::vector<std::string>& pass_names() const { return pass_names_; }

private:
    // Query objects of one frame in flight: [frame begin, pass0 begin, pass0 end, ..., frame end].
    struct InFlight {
        std::vector<GLuint> queries;
        size_t used = 0;
        size_t frame = 0;                                // index into frames_
        uint64_t issued = 0;                             // pathlet::gpu_frame() when its queries were issued
        size_t frame_begin = 0, frame_end = 0;           // query positions
        std::vector<std::array<size_t, 2>> pass_stamps;  // per pass sample: begin, end
    };
    // Collected query sets are recycled, so a GPU keeping up cycles through 3-4 of them. The
    // executor keeps at most PATHLET_FRAMES_IN_FLIGHT frames in flight; results may still come
    // later (a GPU's bursts, the simulated latency), so the ring grows. Beyond kMaxInFlight the
    // oldest frame is waited for (and that said once), never dropped.
    static constexpr size_t kMaxInFlight = 64;

    double now() const;
    double measure() const;            // the backend's clock: now(), or the process's CPU time (CpuTime)
    int pass_id(const std::string& name);
    void sync_point();                 // glFinish for CpuFinish and CpuTime
    size_t stamp();                    // glQueryCounter for GlTimestamp; returns query position
    bool try_collect(InFlight& slot, bool wait);  // true when collected
    InFlight& current() { return in_flight_.back(); }
    bool measured(const FrameRecord& f) const { return !f.warmup; }

    TimingBackend backend_ = TimingBackend::CpuFinish;
    std::string description_ = "not initialised";
    int warmup_frames_ = 3;
    double warmup_seconds_ = 0;
    bool warmup_settled_ = true;
    double wall_end_ms_ = 0;        // when flush() saw every recorded frame done
    size_t wall_end_frames_ = 0;    // frames_.size() then
    std::function<double()> clock_;
    double epoch_ms_ = 0, cpu_epoch_ms_ = 0;
    double gl_to_cpu_ms_ = 0;  // added to GL timestamps (ms) to land on the profiler clock

    std::vector<std::string> pass_names_;
    std::vector<int> pass_depth_;  // nesting depth where first seen, for indenting reports
    std::map<std::string, int> pass_ids_;
    std::vector<FrameRecord> frames_;
    std::vector<size_t> open_passes_;  // indices into the current frame's passes
    bool in_frame_ = false;
    uint64_t frames_begun_ = 0;

    std::deque<InFlight> in_flight_;               // oldest first
    std::vector<std::vector<GLuint>> spare_sets_;  // query objects of collected frames, for reuse
    size_t dropped_ = 0;
    bool said_behind_ = false;

    struct StatAccum {
        double sum = 0;
        size_t n = 0;
    };
    std::map<int, std::map<std::string, StatAccum>> stats_;
};

// Percentiles by linear interpolation between the sorted samples (NumPy's default).
Profiler::Stats compute_stats(std::vector<double> samples);
double percentile_sorted(const std::vector<double>& sorted, double p);  // p in [0,1]

}  // namespace pathlet
