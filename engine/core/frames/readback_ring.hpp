// Texture read-back that does not wait for the GPU: each copy goes into a pixel-pack buffer
// (glGetTextureImage with the buffer bound), one fence follows a frame's copies, and the bytes
// are handed over once the fence has signalled: poll() after every frame takes what is ready
// without waiting, and only when `depth` frames are in flight does end_frame() wait for the
// oldest. So frame N+1 renders while frame N is copied. The pack buffers are mapped once, for
// good (persistent, coherent): a hand-over is a pointer into one, read by a writer thread, and
// the render thread copies nothing. A size no frame copies any more (the viewer's window was
// resized) leaves no buffers behind: end_frame() frees the free ones of other sizes. GL thread
// only (the PackedPixels excepted); the context must be current for every call, the destructor
// included, and every PackedPixels must be gone before the destructor runs.
#pragma once

#include "frames/raw_frame.hpp"

#include <pathlet/gpu_fence.hpp>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pathlet {

class ReadbackRing {
public:
    // The copy's bytes as glGetTextureImage packs them (rows bottom-up, 4-byte aligned rows),
    // where they lie in the mapped buffer; the buffer is not reused while the PackedPixels (or
    // a copy of it) lives. Called on the GL thread, in copy order.
    using Done = std::function<void(PackedPixels&& data)>;

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
    uint64_t bytes_copied() const { return bytes_copied_; }  // into pack buffers, so far
    size_t depth() const { return depth_; }
    size_t buffers() const { return free_.size() + busy_buffers(); }  // pack buffers held now

private:
    struct Lease {
        std::atomic<bool> in_use{false};  // a PackedPixels of the buffer lives (any thread)
    };
    struct Buffer {
        GLuint id = 0;
        size_t size = 0;
        const uint8_t* mapped = nullptr;  // for good
        std::shared_ptr<Lease> lease;
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
    void drop_unused_sizes();  // frees free buffers of sizes the open frame does not copy
    void take(Frame& f);  // hands over, recycles the buffers (leased)
    void take_oldest(bool wait);
    size_t busy_buffers() const;

    size_t depth_;
    uint64_t bytes_copied_ = 0;
    std::deque<Frame> frames_;  // fenced, oldest first
    Frame open_;                // copies of the frame being recorded
    std::vector<Buffer> free_;  // not in a frame; leased ones are taken once released
};

}  // namespace pathlet
