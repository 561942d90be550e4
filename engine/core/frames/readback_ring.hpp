// Texture read-back that does not wait for the GPU: each copy goes into a pixel-pack buffer
// (glGetTextureImage with the buffer bound), one fence follows a frame's copies, and the bytes
// are taken once the fence has signalled: poll() after every frame takes what is ready without
// waiting, and only when `depth` frames are in flight does end_frame() wait for the oldest.
// So frame N+1 renders while frame N is copied. GL thread only; the context must be current
// for every call, the destructor included.
#pragma once

#include <pathlet/gpu_fence.hpp>

#include <cstddef>
#include <deque>
#include <functional>
#include <string>
#include <vector>

namespace pathlet {

class ReadbackRing {
public:
    // The copy's bytes as glGetTextureImage packs them (rows bottom-up, 4-byte aligned rows),
    // in a float vector (byte reads use its storage as bytes). Runs on the GL thread, in copy order.
    using Done = std::function<void(std::vector<float>&& data)>;

    explicit ReadbackRing(size_t depth = 3);  // frames in flight, >= 1
    ~ReadbackRing();
    ReadbackRing(const ReadbackRing&) = delete;
    ReadbackRing& operator=(const ReadbackRing&) = delete;

    // Queues a copy of level 0 of `tex` (w x h) as (format, type), bytes_per_pixel each.
    // `what` names it in errors (a GL error here means the texture cannot be read that way).
    void copy(GLuint tex, int w, int h, GLenum format, GLenum type, int bytes_per_pixel, Done done,
              const std::string& what);
    // Ends the frame's copies with a fence; when `depth` frames are in flight, waits for the oldest.
    void end_frame();
    void poll();   // takes every frame whose fence has signalled, oldest first, never waiting
    void drain();  // waits for and takes every frame in flight

    size_t in_flight() const { return frames_.size(); }
    size_t depth() const { return depth_; }
    size_t buffers() const { return free_.size() + busy_buffers(); }  // pack buffers made so far

private:
    struct Buffer {
        GLuint id = 0;
        size_t size = 0;
    };
    struct Copy {
        Buffer buffer;
        size_t bytes = 0;
        Done done;
    };
    struct Frame {
        std::vector<Copy> copies;
        GpuFence fence;  // checked through pathlet/gpu_fence.hpp (the simulated latency too)
    };
    Buffer take_buffer(size_t bytes);
    void take(Frame& f);  // maps, hands over, recycles the buffers
    void take_oldest(bool wait);
    size_t busy_buffers() const;

    size_t depth_;
    std::deque<Frame> frames_;  // fenced, oldest first
    Frame open_;                // copies of the frame being recorded
    std::vector<Buffer> free_;
};

}  // namespace pathlet
