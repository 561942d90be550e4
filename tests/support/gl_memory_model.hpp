// A checker of the GL memory model's update barriers around the real GL stack, for tests: a
// test executable that links it (pathlet_gl_memory_model, with ENABLE_EXPORTS) interposes the GL
// calls that bind shader-written memory, draw, dispatch, issue barriers and clear or update
// textures and buffers, records them, and forwards every call to the driver unchanged.
//
// The rule it checks (GL 4.5 section 7.12.2): a texture a shader could write through an image
// unit, or a buffer it could write as a storage block (or an image buffer), is cleared or updated
// by a GL command (glClearTexImage, glClearTexSubImage, glClearNamedBufferData,
// glClearNamedBufferSubData, glNamedBufferSubData) only after a glMemoryBarrier with
// GL_TEXTURE_UPDATE_BARRIER_BIT (textures) or GL_BUFFER_UPDATE_BARRIER_BIT (buffers) since the
// draw or dispatch that had it bound. The barrier must come from the pass that wrote (after its
// writes) or from the pass that clears (before its clear): a third pass's barrier that happens to
// fall in between is luck, not a guarantee. Passes are told apart by the executor's debug groups,
// which the checker switches on (PATHLET_GL_DEBUG=1) when the executable starts.
//
// Drivers run shader writes and clears in order more often than not (llvmpipe always), so a
// missing barrier shows no wrong pixel here; the checker sees it on any driver.
#pragma once

#include <string>
#include <vector>

namespace pathlet::gl_memory_model {

struct Violation {
    std::string pass;      // the pass that cleared or updated ("" outside any pass)
    std::string call;      // "glClearTexImage"
    std::string resource;  // "texture 12", "buffer 7"
    std::string writer;    // the pass whose draw or dispatch had it bound
    std::string str() const;
};

// Forgets what was bound and written, and the violations so far.
void reset();
// The violations since the last reset or take, each once per (pass, call, writer) with a count.
std::vector<std::string> take_violations();
// Whether the interposer is in the executable (false: the checker sees nothing; a test asserts it).
bool active();

// While on, glMapNamedBufferRange fails (returns null without mapping), as a driver out of
// address space would.
void fail_buffer_maps(bool on);

}  // namespace pathlet::gl_memory_model
