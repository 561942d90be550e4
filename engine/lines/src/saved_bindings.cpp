#include "saved_bindings.hpp"

namespace pathlet::lines {

SavedBindings::SavedBindings(GLuint storage_points, GLuint texture_unit, GLuint image_unit)
    : ssbo_(storage_points), texture_unit_(texture_unit), image_unit_(image_unit) {
    for (GLuint i = 0; i < storage_points; ++i) {
        glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &ssbo_[i].buffer);
        if (!ssbo_[i].buffer) continue;
        glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, i, &ssbo_[i].start);
        glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, i, &ssbo_[i].size);
    }
    if (storage_points) glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &generic_);
    if (texture_unit != kNone) {
        glGetIntegerv(GL_ACTIVE_TEXTURE, &active_);
        glActiveTexture(GL_TEXTURE0 + texture_unit);
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture2d_);
        glGetIntegerv(GL_TEXTURE_BINDING_3D, &texture3d_);
        glActiveTexture(GLenum(active_));
    }
    if (image_unit != kNone) {
        glGetIntegeri_v(GL_IMAGE_BINDING_NAME, image_unit, &image_.name);
        if (image_.name) {
            glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, image_unit, &image_.level);
            glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, image_unit, &image_.layer);
            glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, image_unit, &image_.access);
            glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, image_unit, &image_.format);
            glGetBooleani_v(GL_IMAGE_BINDING_LAYERED, image_unit, &image_.layered);
        }
    }
}

void SavedBindings::restore() const {
    for (GLuint i = 0; i < GLuint(ssbo_.size()); ++i) {
        const Range& r = ssbo_[i];
        if (r.buffer && r.size > 0)
            glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, GLuint(r.buffer), GLintptr(r.start), GLsizeiptr(r.size));
        else
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, GLuint(r.buffer));
    }
    if (!ssbo_.empty()) glBindBuffer(GL_SHADER_STORAGE_BUFFER, GLuint(generic_));
    if (texture_unit_ != kNone) {
        // glBindTextureUnit binds to the texture's own target, leaving the unit's others alone.
        // The active unit is the one saved: the helpers bind by unit (glBindTextureUnit).
        glActiveTexture(GL_TEXTURE0 + texture_unit_);
        glBindTexture(GL_TEXTURE_2D, GLuint(texture2d_));
        glBindTexture(GL_TEXTURE_3D, GLuint(texture3d_));
        glActiveTexture(GLenum(active_));
    }
    if (image_unit_ != kNone)
        glBindImageTexture(image_unit_, GLuint(image_.name), image_.level, image_.layered, image_.layer,
                           GLenum(image_.access), GLenum(image_.format ? image_.format : GL_R8));
}

}  // namespace pathlet::lines
