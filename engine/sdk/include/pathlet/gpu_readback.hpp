// A few bytes of a GPU buffer read back without waiting: each copy goes into a slot of a small
// persistently mapped ring with a fence, and poll() hands out the newest copy whose fence has
// signalled. On llvmpipe that is usually the same frame; on a GPU a frame or two later. For
// counts and statistics a pass reports (chunks culled, nodes per pixel), never for what a frame
// depends on.
#pragma once

#include <pathlet/gl.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pathlet {

class GpuReadback {
public:
    // `bytes` per copy, `slots` copies in flight at most (a frame whose copy finds every slot
    // still in flight copies nothing).
    explicit GpuReadback(size_t bytes, int slots = 4);
    GpuReadback(const GpuReadback&) = delete;
    GpuReadback& operator=(const GpuReadback&) = delete;
    ~GpuReadback();  // needs the GL context current

    // Copies `bytes` from `buffer` at `offset` (a GL copy; what shaders wrote needs a
    // GL_BUFFER_UPDATE_BARRIER_BIT first) and fences it, with `tag`: what the caller knew when
    // it copied (e.g. the capacity the count is to be compared with). False when every slot is
    // in flight.
    bool copy(GLuint buffer, size_t offset, uint64_t tag = 0);
    // The newest copy the GPU has finished since the last call, or nullptr; never waits.
    const void* poll();
    // The tag of the copy poll() last returned.
    uint64_t latest_tag() const { return latest_tag_; }

private:
    size_t bytes_, stride_;
    GLuint buffer_ = 0;
    const unsigned char* mapped_ = nullptr;
    std::vector<GLsync> fence_;
    std::vector<uint64_t> tag_;  // per slot, its copy's tag
    uint64_t latest_tag_ = 0;
    std::vector<unsigned char> latest_;
    int next_ = 0;  // the slot the next copy goes to; the oldest in flight is at next_ too when all are
};

}  // namespace pathlet
