// Pixel pack or unpack state at GL's defaults (no bound pixel buffer, alignment 4, no row
// length, no skips) while the object lives, then the caller's state back: what a pass left
// (a bound pixel buffer, a row length) would redirect or skew a read-back or an upload.
#pragma once

#include <pathlet/gl.hpp>

namespace pathlet {

class PlainPixelStore {
public:
    enum Direction { pack, unpack };
    explicit PlainPixelStore(Direction d) : pack_(d == pack) {
        for (int i = 0; i < kNames; ++i) glGetIntegerv(name(i), &saved_[i]);
        glBindBuffer(target(), 0);
        for (int i = 1; i < kNames; ++i) glPixelStorei(name(i), i == 1 ? 4 : 0);
    }
    ~PlainPixelStore() {
        glBindBuffer(target(), GLuint(saved_[0]));
        for (int i = 1; i < kNames; ++i) glPixelStorei(name(i), saved_[i]);
    }
    PlainPixelStore(const PlainPixelStore&) = delete;
    PlainPixelStore& operator=(const PlainPixelStore&) = delete;

private:
    static constexpr int kNames = 5;  // the buffer binding, then the store parameters
    GLenum target() const { return pack_ ? GL_PIXEL_PACK_BUFFER : GL_PIXEL_UNPACK_BUFFER; }
    GLenum name(int i) const {
        static const GLenum kPack[kNames] = {GL_PIXEL_PACK_BUFFER_BINDING, GL_PACK_ALIGNMENT, GL_PACK_ROW_LENGTH,
                                             GL_PACK_SKIP_ROWS, GL_PACK_SKIP_PIXELS};
        static const GLenum kUnpack[kNames] = {GL_PIXEL_UNPACK_BUFFER_BINDING, GL_UNPACK_ALIGNMENT, GL_UNPACK_ROW_LENGTH,
                                               GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_PIXELS};
        return pack_ ? kPack[i] : kUnpack[i];
    }
    bool pack_;
    GLint saved_[kNames] = {};
};

}  // namespace pathlet
