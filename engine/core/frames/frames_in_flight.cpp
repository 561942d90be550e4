#include "frames/frames_in_flight.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace pathlet {

int FramesInFlight::from_env() {
    static const int f = [] {
        const char* v = std::getenv("PATHLET_FRAMES_IN_FLIGHT");
        if (!v || !*v) return 2;
        char* end = nullptr;
        const long n = std::strtol(v, &end, 10);
        if (*end != '\0' || n < 1 || n > 16)
            throw std::runtime_error(std::string("PATHLET_FRAMES_IN_FLIGHT='") + v +
                                     "': expected a whole number of frames 1..16 (default 2)");
        return int(n);
    }();
    return f;
}

FramesInFlight::FramesInFlight(int frames) : limit_(frames < 1 ? 1 : frames) {}

void FramesInFlight::begin_frame() {
    // A real wait, never simulated (pathlet/gpu_fence.hpp): the frames before were flushed.
    while (fences_.size() >= size_t(limit_)) {
        fences_.front().wait();
        fences_.pop_front();
    }
}

void FramesInFlight::end_frame() { fences_.push_back(GpuFence::insert()); }

}  // namespace pathlet
