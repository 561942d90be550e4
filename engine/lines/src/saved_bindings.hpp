// What a kit helper that runs its own dispatches in the middle of a pass (the culling between
// the pass's draws, the density texture before them) changes of the GL bindings, as the pass
// had them: storage buffer points [0, n), one texture unit's 2D and 3D targets and one image
// unit (kNone: a helper that leaves them alone). restore() puts them back, so the pass's own
// buffers, textures and images stay where the executor or the pass put them. (Private to the
// line kit.) GL is asked, because a pass may bind with plain GL calls; only what the helper
// changes is asked (a glGet is a round trip to a threaded driver), and a point's range only
// when a buffer is bound there.
#pragma once

#include <pathlet/gl.hpp>

#include <vector>

namespace pathlet::lines {

class SavedBindings {
public:
    static constexpr GLuint kNone = ~0u;
    SavedBindings(GLuint storage_points, GLuint texture_unit, GLuint image_unit);
    void restore() const;

private:
    struct Range {
        GLint buffer = 0;
        GLint64 start = 0, size = 0;
    };
    std::vector<Range> ssbo_;
    GLuint texture_unit_, image_unit_;
    GLint generic_ = 0, texture2d_ = 0, texture3d_ = 0, active_ = GL_TEXTURE0;
    struct {
        GLint name = 0, level = 0, layer = 0, access = GL_READ_ONLY, format = 0;
        GLboolean layered = GL_FALSE;
    } image_;
};

}  // namespace pathlet::lines
