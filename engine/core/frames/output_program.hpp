// The small fragment programs of the output side (GpuBoxFilter, GpuDepthCopy): one triangle
// over the viewport and a fragment stage, compiled and linked here once for both. GL thread.
#pragma once

#include <pathlet/gl.hpp>

#include <cstddef>
#include <vector>

namespace pathlet {

// Links the fullscreen triangle with `fragment` (GLSL 450); throws std::runtime_error starting
// with `what` and the driver's log when it does not compile or link.
GLuint link_output_program(const char* fragment, const char* what);

// Draws the fullscreen triangle with `program` into `fbo` (w x h), `src` on texture unit 0 through
// `sampler` (0: the texture's own parameters). Sets what a pass may have left that would change
// what lands in the target (blend, depth, scissor, stencil, culling, colour mask; the executor
// resets these before every pass) and leaves program, framebuffer, vertex array, unit 0 and its
// sampler unbound.
void draw_output_program(GLuint program, GLuint vao, GLuint fbo, int w, int h, GLuint src, GLuint sampler = 0);

// The output programs' render targets, one a slot (a slot is reused frame after frame; a new
// size replaces its texture). GL thread; deletes what it made.
class OutputTargets {
public:
    explicit OutputTargets(GLenum format) : format_(format) {}
    ~OutputTargets() { truncate(0); }
    OutputTargets(const OutputTargets&) = delete;
    OutputTargets& operator=(const OutputTargets&) = delete;

    struct Target {
        GLuint tex = 0, fbo = 0;
        int w = 0, h = 0;
    };
    // The slot's target, made or remade at w x h.
    const Target& at(size_t slot, int w, int h);
    size_t size() const { return targets_.size(); }
    // Deletes the targets from slot `n` on (a measurement's own slot, dropped afterwards).
    void truncate(size_t n);

private:
    GLenum format_;
    std::vector<Target> targets_;
};

}  // namespace pathlet
