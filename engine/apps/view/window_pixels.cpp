#include "view/window_pixels.hpp"

#include "pixel_store.hpp"

#include <cstdint>
#include <vector>

namespace pathlet::view {

OutputBlit::OutputBlit() { glCreateFramebuffers(1, &fbo_); }
OutputBlit::~OutputBlit() { glDeleteFramebuffers(1, &fbo_); }

void OutputBlit::draw(const Texture& tex, glm::ivec2 window) const {
    glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, tex.id, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glViewport(0, 0, window.x, window.y);
    glClearColor(1, 1, 1, 1);  // an output with a transparent background shows on white
    glClear(GL_COLOR_BUFFER_BIT);
    glBlitNamedFramebuffer(fbo_, 0, 0, 0, tex.width, tex.height, 0, 0, window.x, window.y, GL_COLOR_BUFFER_BIT,
                           GL_NEAREST);
}

WindowCopy::~WindowCopy() { release(); }

void WindowCopy::release() {
    if (fbo_) glDeleteFramebuffers(1, &fbo_);
    if (tex_) glDeleteTextures(1, &tex_);
    fbo_ = tex_ = 0;
}

void WindowCopy::copy(glm::ivec2 size) {
    if (size != size_) {
        release();
        glCreateTextures(GL_TEXTURE_2D, 1, &tex_);
        glTextureStorage2D(tex_, 1, GL_RGBA8, size.x, size.y);
        glCreateFramebuffers(1, &fbo_);
        glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, tex_, 0);
        size_ = size;
    }
    glDisable(GL_SCISSOR_TEST);  // a blit is scissored (glReadPixels was not)
    glBlitNamedFramebuffer(0, fbo_, 0, 0, size.x, size.y, 0, 0, size.x, size.y, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

Image WindowCopy::read() const {
    Image img;
    img.width = size_.x, img.height = size_.y, img.channels = 4;
    const size_t row = size_t(size_.x) * 4;
    std::vector<uint8_t> px(row * size_t(size_.y));
    {
        const PlainPixelStore plain(PlainPixelStore::pack);
        glGetTextureImage(tex_, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(px.size()), px.data());
    }
    img.pixels.resize(px.size());
    for (int y = 0; y < size_.y; ++y)  // GL rows are bottom-up
        for (size_t x = 0; x < row; ++x)
            img.pixels[size_t(y) * row + x] = float(px[size_t(size_.y - 1 - y) * row + x]) / 255.0f;
    return img;
}

}  // namespace pathlet::view
