#include <pathlet/gpu_readback.hpp>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace pathlet {

namespace {
constexpr GLbitfield kMapFlags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
}

GpuReadback::GpuReadback(size_t bytes, int slots, int max_slots)
    : bytes_(std::max<size_t>(bytes, 1)), stride_((std::max<size_t>(bytes, 1) + 15) / 16 * 16),
      per_block_(size_t(std::max(slots, 1))), max_slots_(std::max(size_t(std::max(max_slots, 1)), size_t(1))) {
    per_block_ = std::min(per_block_, max_slots_);
    grow();
}

GpuReadback::~GpuReadback() {
    pending_.clear();  // deletes the fences
    for (const Block& b : blocks_) {
        glUnmapNamedBuffer(b.buffer);
        glDeleteBuffers(1, &b.buffer);
    }
}

void GpuReadback::grow() {
    const size_t n = std::min(per_block_, max_slots_ - slot_count_);
    Block b;
    const GLsizeiptr size = GLsizeiptr(stride_ * per_block_);
    glCreateBuffers(1, &b.buffer);
    glNamedBufferStorage(b.buffer, size, nullptr, kMapFlags);
    b.mapped = static_cast<const unsigned char*>(glMapNamedBufferRange(b.buffer, 0, size, kMapFlags));
    if (!b.mapped) {  // nothing could be read back: an error, never a lost count
        glDeleteBuffers(1, &b.buffer);
        throw std::runtime_error("read-back: cannot map a buffer of " + std::to_string(size) +
                                 " bytes (glMapNamedBufferRange failed)");
    }
    blocks_.push_back(b);
    // Lowest slot on top of the free list: slots are used in order while the GPU keeps up.
    for (size_t i = n; i-- > 0;) free_.push_back(int(slot_count_ + i));
    slot_count_ += n;
}

const unsigned char* GpuReadback::slot_bytes(int slot) const {
    return blocks_[size_t(slot) / per_block_].mapped + (size_t(slot) % per_block_) * stride_;
}

void GpuReadback::copy(GLuint buffer, size_t offset, uint64_t tag, uint64_t frame) {
    if (free_.empty() && slot_count_ < max_slots_) grow();
    if (free_.empty()) {
        // The GPU is max_slots copies behind: the oldest is waited for, not dropped.
        for (Pending& p : pending_) {
            if (p.slot < 0) continue;
            p.fence.wait();
            const unsigned char* src = slot_bytes(p.slot);
            p.kept.assign(src, src + bytes_);
            free_.push_back(p.slot);
            p.slot = -1;
            p.fence.reset();
            ++waits_;
            break;
        }
    }
    const int slot = free_.back();
    free_.pop_back();
    const Block& b = blocks_[size_t(slot) / per_block_];
    glCopyNamedBufferSubData(buffer, b.buffer, GLintptr(offset), GLintptr((size_t(slot) % per_block_) * stride_),
                             GLsizeiptr(bytes_));
    Pending p;
    p.slot = slot;
    p.fence = GpuFence::insert();
    p.tag = tag;
    p.frame = frame;
    pending_.push_back(std::move(p));
}

void GpuReadback::hand_out(Pending& p, const Take& take) {
    Result r;
    r.tag = p.tag;
    r.frame = p.frame;
    r.data = p.slot < 0 ? p.kept.data() : slot_bytes(p.slot);
    if (p.slot >= 0) free_.push_back(p.slot);  // before take(), which may throw; nothing copies meanwhile
    if (take) take(r);
}

size_t GpuReadback::poll(const Take& take) {
    size_t n = 0;
    while (!pending_.empty()) {
        Pending& p = pending_.front();
        // The flush bit: a fence nothing has flushed yet would never signal.
        if (p.slot >= 0 && !p.fence.signalled(true)) break;
        Pending done = std::move(p);
        pending_.pop_front();
        hand_out(done, take);
        ++n;
    }
    return n;
}

size_t GpuReadback::drain(const Take& take) {
    size_t n = 0;
    while (!pending_.empty()) {
        Pending done = std::move(pending_.front());
        pending_.pop_front();
        if (done.slot >= 0) done.fence.wait();
        hand_out(done, take);
        ++n;
    }
    return n;
}

const void* GpuReadback::poll_newest() {
    bool got = false;
    poll([&](const Result& r) {
        const auto* b = static_cast<const unsigned char*>(r.data);
        latest_.assign(b, b + bytes_);
        latest_tag_ = r.tag;
        got = true;
    });
    return got ? latest_.data() : nullptr;
}

}  // namespace pathlet
