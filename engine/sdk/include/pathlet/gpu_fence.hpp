// Asking whether the GPU is done, in ONE place: every fence and query result the engine and the
// passes check goes through here, so a GPU's latency can be simulated on any driver.
//
// How to use it:
//   GpuFence f = GpuFence::insert();   // after the GL commands to wait for (stamped with the frame)
//   if (f.signalled()) ...             // never waits; false while the GPU (or the simulation) is busy
//   f.wait();                          // blocks until done (end of a run, a full ring); never simulated
//   if (query_ready(q, issued_frame)) glGetQueryObjectui64v(q, GL_QUERY_RESULT, &ns);
// Never call glClientWaitSync / glGetSynciv / GL_QUERY_RESULT_AVAILABLE yourself.
//
// The frame clock: the executor calls advance_gpu_frame() once at the start of every frame;
// gpu_frame() is the frame being recorded (0 before the first). Fences and queries remember the
// frame they were issued in.
//
// PATHLET_SIMULATE_GPU_LATENCY=K (K >= 1; unset, empty or 0: off): a non-blocking check reads
// "not done" until at least K frames after the issuing frame, and then only in frames whose number
// is a multiple of K, so results arrive late and in bursts of K, as from a GPU behind a busy
// CPU. Blocking waits are real waits (a simulated latency cannot pass while the CPU waits), so
// they never deadlock. docs/testing.md.
#pragma once

#include <pathlet/gl.hpp>

#include <cstdint>

namespace pathlet {

// The frame clock (GL thread).
uint64_t gpu_frame();
void advance_gpu_frame();

// K of PATHLET_SIMULATE_GPU_LATENCY (0: off), read once; throws std::runtime_error naming the
// variable for anything but a whole number 0..1000.
int simulated_gpu_latency();
// Tests: a latency other than the environment's (0: off); a negative value goes back to it.
void set_simulated_gpu_latency(int frames);

// How long a blocking wait (GpuFence::wait) waits before it gives up with an error naming the
// frame the fence was issued in: PATHLET_GPU_WAIT_LIMIT seconds (default 120; a whole GPU frame
// takes far less, but a hung GPU without robustness never signals). Anything but a number > 0
// throws std::runtime_error naming the variable.
double gpu_wait_limit_seconds();
// Tests: a limit other than the environment's; <= 0 goes back to it. And a GPU that never
// signals (every fence and wait reads "not done"), to see the limit act.
void set_gpu_wait_limit(double seconds);
void set_simulated_gpu_hang(bool hung);
// The simulation's rule alone: may a result issued in `issued_frame` be seen now?
bool simulated_latency_passed(uint64_t issued_frame);

// A GL fence sync with the frame it was issued in. Move-only; deletes its sync.
class GpuFence {
public:
    GpuFence() = default;
    static GpuFence insert();  // glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE) now
    GpuFence(GpuFence&& o) noexcept : sync_(o.sync_), frame_(o.frame_) { o.sync_ = nullptr; }
    GpuFence& operator=(GpuFence&& o) noexcept;
    GpuFence(const GpuFence&) = delete;
    GpuFence& operator=(const GpuFence&) = delete;
    ~GpuFence() { reset(); }

    explicit operator bool() const { return sync_ != nullptr; }
    uint64_t frame() const { return frame_; }
    // Done? Never waits. `flush`: GL_SYNC_FLUSH_COMMANDS_BIT, for a fence nothing has flushed yet
    // (it would never signal); the simulation answers false before asking GL at all.
    bool signalled(bool flush = true) const;
    // Waits until done, with the flush bit, a second at a time; throws std::runtime_error when
    // GL reports the wait failed (a lost context) or after gpu_wait_limit_seconds(), naming the
    // frame the fence was issued in. Ignores the simulated latency.
    void wait() const;
    void reset();  // deletes the sync (no wait)

private:
    GLsync sync_ = nullptr;
    uint64_t frame_ = 0;
};

// GL_QUERY_RESULT_AVAILABLE of a query issued in `issued_frame`, under the simulated latency.
bool query_ready(GLuint query, uint64_t issued_frame);

}  // namespace pathlet
