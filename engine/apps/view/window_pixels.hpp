// Pixels on and off the viewer's window: the graph's output drawn on it, and a copy of the
// whole window (output and panels) for --screenshot-window.
#pragma once

#include "image_io.hpp"

#include <pathlet/pass.hpp>

namespace pathlet::view {

// The graph output on the window's framebuffer. Its read framebuffer is made once and kept;
// each frame attaches the output texture (a rebuilt graph may bring another texture).
class OutputBlit {
public:
    OutputBlit();
    ~OutputBlit();
    OutputBlit(const OutputBlit&) = delete;
    OutputBlit& operator=(const OutputBlit&) = delete;
    void draw(const Texture& tex, glm::ivec2 window) const;

private:
    GLuint fbo_ = 0;
};

// The whole window kept on the GPU: the window's pixels are gone after the swap and closing it
// comes unannounced, so each frame is blitted into a texture (no read-back, no wait) and only
// the last one is read, once, at the end.
class WindowCopy {
public:
    WindowCopy() = default;
    ~WindowCopy();
    WindowCopy(const WindowCopy&) = delete;
    WindowCopy& operator=(const WindowCopy&) = delete;
    void copy(glm::ivec2 size);
    bool empty() const { return tex_ == 0; }
    // Top row first, bytes / 255 as glReadPixels of the window gave them.
    Image read() const;

private:
    void release();
    GLuint tex_ = 0, fbo_ = 0;
    glm::ivec2 size_{0};
};

}  // namespace pathlet::view
