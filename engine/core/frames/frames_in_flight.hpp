// How far the CPU may record ahead of the GPU: a fence after every frame, and before frame N a
// wait for frame N - F (F = PATHLET_FRAMES_IN_FLIGHT, default 2). Headless (render, bench,
// --no-images, Python, quality) nothing else throttles the CPU, and a CPU many frames ahead makes
// counts arrive late, the profiler's queries pile up and pipelined uploads hold driver memory.
// Free when the GPU is the bottleneck. Executor::run_frame uses it for every program's loop.
#pragma once

#include <pathlet/gpu_fence.hpp>

#include <cstddef>
#include <deque>

namespace pathlet {

class FramesInFlight {
public:
    explicit FramesInFlight(int frames = from_env());
    // PATHLET_FRAMES_IN_FLIGHT (1..16, default 2); throws std::runtime_error naming the variable.
    static int from_env();

    void begin_frame();  // waits (GL_SYNC_FLUSH_COMMANDS_BIT) until fewer than F frames are in flight
    void end_frame();    // fences the frame just recorded
    int limit() const { return limit_; }
    size_t in_flight() const { return fences_.size(); }

private:
    int limit_;
    std::deque<GpuFence> fences_;  // oldest first
};

}  // namespace pathlet
