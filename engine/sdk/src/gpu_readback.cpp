#include <pathlet/gpu_readback.hpp>

#include <algorithm>
#include <cstring>

namespace pathlet {

GpuReadback::GpuReadback(size_t bytes, int slots)
    : bytes_(std::max<size_t>(bytes, 1)), stride_((std::max<size_t>(bytes, 1) + 15) / 16 * 16),
      fence_(size_t(std::max(slots, 1)), nullptr), tag_(fence_.size(), 0) {
    const GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    const GLsizeiptr size = GLsizeiptr(stride_ * fence_.size());
    glCreateBuffers(1, &buffer_);
    glNamedBufferStorage(buffer_, size, nullptr, flags);
    mapped_ = static_cast<const unsigned char*>(glMapNamedBufferRange(buffer_, 0, size, flags));
}

GpuReadback::~GpuReadback() {
    for (GLsync f : fence_)
        if (f) glDeleteSync(f);
    if (buffer_) {
        glUnmapNamedBuffer(buffer_);
        glDeleteBuffers(1, &buffer_);
    }
}

bool GpuReadback::copy(GLuint buffer, size_t offset, uint64_t tag) {
    if (fence_[size_t(next_)]) poll();  // frees the slot if its copy is done
    if (fence_[size_t(next_)] || !mapped_) return false;
    glCopyNamedBufferSubData(buffer, buffer_, GLintptr(offset), GLintptr(size_t(next_) * stride_), GLsizeiptr(bytes_));
    fence_[size_t(next_)] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    tag_[size_t(next_)] = tag;
    next_ = (next_ + 1) % int(fence_.size());
    return true;
}

const void* GpuReadback::poll() {
    bool got = false;
    const int n = int(fence_.size());
    for (int k = 0; k < n; ++k) {
        const size_t slot = size_t((next_ + k) % n);  // oldest first
        if (!fence_[slot]) continue;
        // FLUSH: a fence nothing has flushed yet would never signal.
        const GLenum r = glClientWaitSync(fence_[slot], GL_SYNC_FLUSH_COMMANDS_BIT, 0);
        if (r != GL_ALREADY_SIGNALED && r != GL_CONDITION_SATISFIED) break;
        glDeleteSync(fence_[slot]);
        fence_[slot] = nullptr;
        latest_.assign(mapped_ + slot * stride_, mapped_ + slot * stride_ + bytes_);
        latest_tag_ = tag_[slot];
        got = true;
    }
    return got ? latest_.data() : nullptr;
}

}  // namespace pathlet
