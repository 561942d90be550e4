#include "frames/readback_ring.hpp"

#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace pathlet {

namespace {

// Pack state set by a pass (a bound pack buffer, row length) would redirect or skew the copy:
// plain settings while we copy, theirs back afterwards.
class PackState {
public:
    explicit PackState(GLuint buffer) {
        glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &buffer_);
        glGetIntegerv(GL_PACK_ALIGNMENT, &alignment_);
        glGetIntegerv(GL_PACK_ROW_LENGTH, &row_length_);
        glGetIntegerv(GL_PACK_SKIP_ROWS, &skip_rows_);
        glGetIntegerv(GL_PACK_SKIP_PIXELS, &skip_pixels_);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glPixelStorei(GL_PACK_ROW_LENGTH, 0);
        glPixelStorei(GL_PACK_SKIP_ROWS, 0);
        glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
    }
    ~PackState() {
        glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(buffer_));
        glPixelStorei(GL_PACK_ALIGNMENT, alignment_);
        glPixelStorei(GL_PACK_ROW_LENGTH, row_length_);
        glPixelStorei(GL_PACK_SKIP_ROWS, skip_rows_);
        glPixelStorei(GL_PACK_SKIP_PIXELS, skip_pixels_);
    }

private:
    GLint buffer_ = 0, alignment_ = 4, row_length_ = 0, skip_rows_ = 0, skip_pixels_ = 0;
};

size_t row_bytes(int w, int bytes_per_pixel) { return (size_t(w) * size_t(bytes_per_pixel) + 3) / 4 * 4; }

}  // namespace

ReadbackRing::ReadbackRing(size_t depth) : depth_(depth < 1 ? 1 : depth) {}

ReadbackRing::~ReadbackRing() {
    auto release = [](const Buffer& b) { glDeleteBuffers(1, &b.id); };
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
    // Sizes repeat frame after frame: the smallest free buffer that fits.
    size_t best = free_.size();
    for (size_t i = 0; i < free_.size(); ++i)
        if (free_[i].size >= bytes && (best == free_.size() || free_[i].size < free_[best].size)) best = i;
    if (best < free_.size()) {
        Buffer b = free_[best];
        free_.erase(free_.begin() + long(best));
        return b;
    }
    Buffer b;
    b.size = bytes;
    glCreateBuffers(1, &b.id);
    // Read by the CPU only: client storage asks for memory the CPU reads fast.
    glNamedBufferStorage(b.id, GLsizeiptr(bytes), nullptr, GL_MAP_READ_BIT | GL_CLIENT_STORAGE_BIT);
    return b;
}

void ReadbackRing::copy(GLuint tex, int w, int h, GLenum format, GLenum type, int bytes_per_pixel, Done done,
                        const std::string& what) {
    const size_t bytes = row_bytes(w, bytes_per_pixel) * size_t(h);
    Copy c;
    c.buffer = take_buffer(bytes);
    c.bytes = bytes;
    c.done = std::move(done);
    GLenum err = GL_NO_ERROR;
    {
        PackState pack(c.buffer.id);
        while (glGetError() != GL_NO_ERROR) {}  // earlier errors are not ours (KHR_debug reports them)
        glGetTextureImage(tex, 0, format, type, GLsizei(bytes), nullptr);
        err = glGetError();
    }
    if (err != GL_NO_ERROR) {
        free_.push_back(c.buffer);
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", unsigned(err));
        throw std::runtime_error(what + ": cannot read the texture back (glGetTextureImage: GL error " + code + ")");
    }
    open_.copies.push_back(std::move(c));
}

void ReadbackRing::end_frame() {
    if (open_.copies.empty()) return;
    open_.fence = GpuFence::insert();
    glFlush();  // the fence can signal without our next wait having to flush it
    frames_.push_back(std::move(open_));
    open_ = {};
    while (frames_.size() > depth_) take_oldest(true);
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
    // Every buffer goes back to the free list before a hand-over can throw.
    std::vector<std::pair<std::vector<float>, Done>> ready;
    bool mapped = true;
    for (Copy& c : f.copies) {
        std::vector<float> data;
        if (const void* p = mapped ? glMapNamedBufferRange(c.buffer.id, 0, GLsizeiptr(c.bytes), GL_MAP_READ_BIT) : nullptr) {
            data.resize((c.bytes + 3) / 4);
            std::memcpy(data.data(), p, c.bytes);
            glUnmapNamedBuffer(c.buffer.id);
        } else {
            mapped = false;
        }
        free_.push_back(c.buffer);
        ready.emplace_back(std::move(data), std::move(c.done));
    }
    f.copies.clear();
    if (!mapped) throw std::runtime_error("read-back: cannot map a pixel-pack buffer");
    for (auto& [data, done] : ready) done(std::move(data));
}

}  // namespace pathlet
