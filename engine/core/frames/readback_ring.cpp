#include "frames/readback_ring.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace pathlet {

namespace {

// Pack state a pass set (a bound pack buffer, a row length; passes need not restore it) would
// redirect or skew the copy: set, not asked (a glGet is a round trip to a threaded driver), and
// GL's defaults left behind.
void plain_pack_state(GLuint buffer) {
    glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glPixelStorei(GL_PACK_SKIP_ROWS, 0);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
}

bool gl_debug() {
    static const bool on = std::getenv("PATHLET_GL_DEBUG") != nullptr;
    return on;
}

size_t row_bytes(int w, int bytes_per_pixel) { return (size_t(w) * size_t(bytes_per_pixel) + 3) / 4 * 4; }

}  // namespace

ReadbackRing::ReadbackRing(size_t depth) : depth_(depth < 1 ? 1 : depth) {}

ReadbackRing::~ReadbackRing() {
    auto release = [](const Buffer& b) { glDeleteBuffers(1, &b.id); };  // unmaps it
    for (Frame& f : frames_) {
        f.fence.reset();
        for (Copy& c : f.copies) release(c.buffer);
    }
    for (Copy& c : open_.copies) release(c.buffer);
    for (const Buffer& b : free_) release(b);
}

size_t ReadbackRing::busy_buffers() const {
    size_t n = open_.copies.size();
    for (const Frame& f : frames_) n += f.copies.size();
    return n;
}

ReadbackRing::Buffer ReadbackRing::take_buffer(size_t bytes) {
    // Sizes repeat frame after frame: the smallest free buffer that fits, once its last reader
    // (a writer widening the pixels straight out of it) is done.
    size_t best = free_.size();
    for (size_t i = 0; i < free_.size(); ++i)
        if (free_[i].size >= bytes && !free_[i].lease->in_use.load(std::memory_order_acquire) &&
            (best == free_.size() || free_[i].size < free_[best].size))
            best = i;
    if (best < free_.size()) {
        Buffer b = free_[best];
        free_.erase(free_.begin() + long(best));
        return b;
    }
    Buffer b;
    b.size = bytes;
    glCreateBuffers(1, &b.id);
    // Read by the CPU only: client storage asks for memory the CPU reads fast. Mapped once, for
    // good: coherent, so what the GPU wrote is there once the frame's fence has signalled.
    const GLbitfield access = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    glNamedBufferStorage(b.id, GLsizeiptr(bytes), nullptr, access | GL_CLIENT_STORAGE_BIT);
    b.mapped = static_cast<const uint8_t*>(glMapNamedBufferRange(b.id, 0, GLsizeiptr(bytes), access));
    if (!b.mapped) {
        glDeleteBuffers(1, &b.id);
        throw std::runtime_error("read-back: cannot map a pixel-pack buffer");
    }
    b.lease = std::make_shared<Lease>();
    return b;
}

void ReadbackRing::copy(GLuint tex, int w, int h, GLenum format, GLenum type, int bytes_per_pixel, Done done,
                        const std::string& what) {
    const size_t bytes = row_bytes(w, bytes_per_pixel) * size_t(h);
    Copy c;
    c.buffer = take_buffer(bytes);
    c.bytes = bytes;
    c.done = std::move(done);
    // Errors are the debug callback's (the executor names them); a glGetError here would be a
    // round trip to a threaded driver every copy, so it is asked only with PATHLET_GL_DEBUG.
    GLenum err = GL_NO_ERROR;
    if (gl_debug())
        while (glGetError() != GL_NO_ERROR) {}  // earlier errors are not ours (KHR_debug reports them)
    plain_pack_state(c.buffer.id);
    glGetTextureImage(tex, 0, format, type, GLsizei(bytes), nullptr);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    if (gl_debug()) err = glGetError();
    if (err != GL_NO_ERROR) {
        free_.push_back(c.buffer);
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", unsigned(err));
        throw std::runtime_error(what + ": cannot read the texture back (glGetTextureImage: GL error " + code + ")");
    }
    bytes_copied_ += bytes;
    open_.copies.push_back(std::move(c));
}

void ReadbackRing::end_frame() {
    if (open_.copies.empty()) return;
    drop_unused_sizes();
    open_.fence = GpuFence::insert();
    glFlush();  // the fence can signal without our next wait having to flush it
    frames_.push_back(std::move(open_));
    open_ = {};
    while (frames_.size() > depth_) take_oldest(true);
}

void ReadbackRing::drop_unused_sizes() {
    // A size this frame did not copy is one a resize left behind (the viewer's window): its
    // free buffers go, once no reader holds them. Busy ones go when they come back free.
    auto used = [&](size_t bytes) {
        for (const Copy& c : open_.copies)
            if (c.bytes == bytes) return true;
        return false;
    };
    for (size_t i = free_.size(); i-- > 0;) {
        const Buffer& b = free_[i];
        if (used(b.size) || b.lease->in_use.load(std::memory_order_acquire)) continue;
        glDeleteBuffers(1, &b.id);  // unmaps it
        free_.erase(free_.begin() + long(i));
    }
}

void ReadbackRing::poll() {
    while (!frames_.empty()) {
        if (!frames_.front().fence.signalled(false)) return;  // flushed in end_frame()
        take_oldest(false);
    }
}

void ReadbackRing::drain() {
    end_frame();
    while (!frames_.empty()) take_oldest(true);
}

void ReadbackRing::take_oldest(bool wait) {
    Frame f = std::move(frames_.front());
    frames_.pop_front();
    if (wait) {
        try {
            f.fence.wait();
        } catch (const std::exception& e) {
            for (Copy& c : f.copies) free_.push_back(c.buffer);
            throw std::runtime_error(std::string("read-back: ") + e.what());
        }
    }
    f.fence.reset();
    take(f);
}

void ReadbackRing::take(Frame& f) {
    // No copy here: each hand-over reads the mapped buffer where it lies, and the buffer goes
    // back to the free list leased until the last PackedPixels of it is gone.
    std::vector<std::pair<PackedPixels, Done>> ready;
    for (Copy& c : f.copies) {
        Buffer b = c.buffer;
        b.lease->in_use.store(true, std::memory_order_relaxed);
        PackedPixels p;
        p.data = b.mapped;
        p.size = c.bytes;
        p.keep = std::shared_ptr<const void>(nullptr, [lease = b.lease](const void*) {
            lease->in_use.store(false, std::memory_order_release);
        });
        free_.push_back(b);
        ready.emplace_back(std::move(p), std::move(c.done));
    }
    f.copies.clear();
    for (auto& [pixels, done] : ready) done(std::move(pixels));
}

}  // namespace pathlet
