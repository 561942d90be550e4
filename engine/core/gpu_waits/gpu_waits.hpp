// Waits for the GPU inside the frame loop, counted per pass: the stall the late read-back
// (pathlet/gpu_readback.hpp) exists to avoid. A pass waits when, inside its execute(), it
//   reads GPU results synchronously: glGet(Named)BufferSubData; glReadPixels, glGetTexImage and
//     their n-, Texture- and Compressed- forms while no pixel-pack buffer is bound (with one
//     bound they are GPU copies);
//   calls glFinish, or glClientWaitSync with a timeout above 0;
//   reads GL_QUERY_RESULT of a query (no query buffer bound) without having seen
//     GL_QUERY_RESULT_AVAILABLE true since the query was issued;
//   maps a buffer for reading other than persistently (a persistent map is made once and read
//     after a fence, as GpuReadback does; GL allows no unsynchronised read map).
// glWaitSync is not a wait: the GPU waits, the CPU goes on.
//
// How: libpathlet defines those GL entry points itself (gl_interpose.cpp). A pass plugin and
// libpathlet call glvnd's libOpenGL directly (pathlet/gl.hpp), and the dynamic linker searches
// libpathlet before libOpenGL (every plugin and program lists it first), so their calls reach the
// definitions here, which count and forward to libOpenGL's (dlsym(RTLD_NEXT)). No pass changes.
// Only calls made while Executor::run_frame runs a pass's execute() count, on that thread: the
// engine's own waits (the profiler's glFinish brackets on llvmpipe, frames in flight, the end of
// a run) do not. A pass's first frame after setup() is counted apart and allowed (fill_list waits
// for its first count, a volume AO reads its grid's size once).
//
// Counting is on under PATHLET_GL_DEBUG and the latency mode (PATHLET_SIMULATE_GPU_LATENCY >= 1);
// off, the entry points only forward (one test of a flag), and nothing is tracked.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace pathlet {

struct PassTypeInfo;
class Params;

// One pass's waits over a run.
struct GpuWaitCount {
    uint64_t first_frame = 0;  // calls in its first frame after setup() (allowed)
    uint64_t later = 0;        // calls in every later frame
    uint64_t frames = 0;       // later frames with at least one
    uint64_t first_waiting_frame = 0;  // the first of those (FrameInfo::index)
    std::map<std::string, uint64_t> calls;  // later frames' calls by entry point
};

// Is counting on? PATHLET_GL_DEBUG set, or a simulated GPU latency (pathlet/gpu_fence.hpp).
bool gpu_wait_counting();
// Tests: 1 on, 0 off whatever the environment says; -1 back to the environment.
void set_gpu_wait_counting(int on);

// May this pass wait in the frame loop? Its type declares so (PassTypeBuilder::waits_for_gpu),
// and the bool parameter the declaration names, if any, is true.
bool gpu_wait_allowed(const PassTypeInfo& type, const Params& params);

// The counts of one executor's passes, by pass index.
class GpuWaitCounter {
public:
    void reset(size_t passes);
    // The pass was (re)set up: its next frame is a first frame.
    void set_up(size_t pass);
    const std::vector<GpuWaitCount>& counts() const { return counts_; }

    // While alive (around one pass's execute()), this thread's waits count for `pass` of `frame`;
    // a no-op when counting is off.
    class Scope {
    public:
        Scope(GpuWaitCounter& counter, size_t pass, uint64_t frame);
        ~Scope();
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        GpuWaitCount* count_ = nullptr;
        uint64_t later_before_ = 0, frame_ = 0;
    };

private:
    std::vector<GpuWaitCount> counts_;
    std::vector<bool> first_frame_;  // by pass: its next frame is its first after setup()
};

// One line about a pass's waits for stderr ("" when it did not wait after its first frame):
// a fault naming the pass, its type, the calls and frames, or, for an allowed wait, its reason.
std::string gpu_wait_line(const std::string& pass, const PassTypeInfo& type, const Params& params,
                          const GpuWaitCount& count);

namespace gpu_waits_detail {
// Called by the interposed entry points: counts `call` for the pass running on this thread.
void note(const char* call);
// Is a pass being counted on this thread (a Scope alive)?
bool counting_here();
}  // namespace gpu_waits_detail

}  // namespace pathlet
