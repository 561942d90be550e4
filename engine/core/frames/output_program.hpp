// The small fragment programs of the output side (GpuBoxFilter, GpuDepthCopy): one triangle
// over the viewport and a fragment stage, compiled and linked here once for both. GL thread.
#pragma once

#include <pathlet/gl.hpp>

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

}  // namespace pathlet
