// A few bytes of a GPU buffer read back without waiting: each copy goes into a slot of a
// persistently mapped ring with a fence (pathlet/gpu_fence.hpp), and poll() hands EVERY copy the
// GPU has finished to its owner, oldest first, with the tag and frame the caller gave it. On
// llvmpipe that is usually the next frame; on a GPU a few frames later, in bursts.
//
// No copy is lost: copy() never polls, and when every slot is in flight the ring grows (a GPU
// behind by more frames than it has slots). Only at `max_slots` does a copy wait, for the oldest
// copy in flight (a synchronous check, counted in waits()), whose bytes are kept for the next
// poll, in order. drain() waits for every copy in flight (the end of a run). For counts and
// statistics a pass reports (nodes, chunks culled), never for what the frame itself draws.
#pragma once

#include <pathlet/gl.hpp>
#include <pathlet/gpu_fence.hpp>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

namespace pathlet {

class GpuReadback {
public:
    // One finished copy; `data` (bytes() long) is valid only during the call that hands it out.
    struct Result {
        const void* data = nullptr;
        uint64_t tag = 0;    // what the caller knew when it copied (e.g. the capacity a count is checked against)
        uint64_t frame = 0;  // the caller's frame (PassContext::frame_index())
    };
    using Take = std::function<void(const Result&)>;

    // `bytes` per copy; `slots` in the ring at first, grown (by `slots` at a time) up to
    // `max_slots` copies in flight.
    explicit GpuReadback(size_t bytes, int slots = 4, int max_slots = 64);
    GpuReadback(const GpuReadback&) = delete;
    GpuReadback& operator=(const GpuReadback&) = delete;
    ~GpuReadback();  // needs the GL context current

    // Copies `bytes` from `buffer` at `offset` (a GL copy; what shaders wrote needs a
    // GL_BUFFER_UPDATE_BARRIER_BIT first) and fences it. Never drops a copy (see above).
    void copy(GLuint buffer, size_t offset, uint64_t tag = 0, uint64_t frame = 0);
    // Hands every finished copy to `take`, oldest first, stopping at the first still in flight
    // (results arrive in copy order); never waits. Returns how many it handed out.
    size_t poll(const Take& take);
    // Waits for every copy in flight and hands each to `take`, in order (the end of a run).
    size_t drain(const Take& take);
    // Statistics only, where an older value is of no use: the newest finished copy (older ones
    // are passed over), or nullptr; never waits. latest_tag() is its tag.
    const void* poll_newest();
    uint64_t latest_tag() const { return latest_tag_; }

    size_t bytes() const { return bytes_; }
    size_t in_flight() const { return pending_.size(); }  // copied, not yet handed out
    size_t slots() const { return slot_count_; }          // slots made so far
    size_t waits() const { return waits_; }               // copies that had to wait (at max_slots)

private:
    struct Block {
        GLuint buffer = 0;
        const unsigned char* mapped = nullptr;
    };
    struct Pending {
        int slot = -1;  // -1: waited for, its bytes in `kept`
        GpuFence fence;
        uint64_t tag = 0, frame = 0;
        std::vector<unsigned char> kept;
    };
    void grow();
    const unsigned char* slot_bytes(int slot) const;
    void hand_out(Pending& p, const Take& take);

    size_t bytes_, stride_, per_block_, max_slots_;
    std::vector<Block> blocks_;
    size_t slot_count_ = 0, waits_ = 0;
    std::vector<int> free_;
    std::deque<Pending> pending_;  // copy order
    uint64_t latest_tag_ = 0;
    std::vector<unsigned char> latest_;
};

}  // namespace pathlet
