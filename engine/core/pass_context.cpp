// PassContext, the SDK's view of one pass (pathlet/pass.hpp), over what the engine keeps for
// it (PassContextImpl) and what it asks of the executor (PassHost).
#include "pass_context.hpp"

#include "frames/async_output.hpp"
#include "image_io.hpp"

#include <algorithm>

namespace pathlet {

std::string pass_label(const CompiledGraph& g, const CompiledPass& p) {
    const std::string where = g.file.empty() ? (p.pointer.empty() ? "" : p.pointer + ": ") : g.file + ":" + p.pointer + ": ";
    return where + "pass '" + p.name + "' (" + p.type->type + ")";
}

PassContextImpl::PassContextImpl(PassHost& h, int i, ShaderSource s) : host(h), index(i), shaders(std::move(s)) {
    take_params();
}

const Binding* PassContextImpl::binding(const std::string& pin) const {
    const auto& b = pass().bindings;
    auto it = b.find(pin);
    return it == b.end() || it->second.resource < 0 ? nullptr : &it->second;
}

void PassContextImpl::unbound(const std::string& pin, const char* what) const {
    throw PassError(pass_label(host.graph(), pass()) + " asked for " + what + " pin '" + pin + "', which is not connected" +
                    (pass().type->pin(pin) ? "" : " (the pass type declares no such pin)"));
}

void PassContextImpl::bind_pins() {
    PassContext ctx(this);
    for (const auto& [pin, unit] : bindings.sampler_pins()) bind_view_or_texture(pin, unit, false);
    for (const auto& [pin, unit] : bindings.image_pins()) bind_view_or_texture(pin, unit, true);
    for (const auto& [pin, point] : bindings.buffers())
        if (ctx.connected(pin)) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(point), ctx.buffer(pin).id);
}

void PassContextImpl::bind_view_or_texture(const std::string& pin, int unit, bool image) {
    PassContext ctx(this);
    if (!ctx.connected(pin)) {
        if (!image) glBindTextureUnit(GLuint(unit), 0);
        return;
    }
    const PinDecl* decl = pass().type->pin(pin);
    const GLenum view = decl ? decl->view : 0;
    const GLuint id = view ? ctx.buffer_texture(pin, view) : ctx.texture(pin).id;
    if (!image) glBindTextureUnit(GLuint(unit), id);
    else glBindImageTexture(GLuint(unit), id, 0, GL_FALSE, 0, GL_READ_WRITE, view ? view : ctx.texture(pin).internal_format);
}

const std::string& PassContext::pass_name() const { return impl_->pass().name; }
const Params& PassContext::params() const { return impl_->params; }
glm::ivec2 PassContext::output_size() const { return impl_->host.graph().output_size; }
float PassContext::pixel_scale() const { return impl_->host.graph().pixel_scale; }
bool PassContext::connected(const std::string& pin) const { return impl_->binding(pin) != nullptr; }

Texture PassContext::texture(const std::string& pin) const {
    const Binding* b = impl_->binding(pin);
    if (!b) impl_->unbound(pin, "texture");
    const auto& ph = impl_->host.physical(b->resource, b->previous);
    if (!ph.tex) impl_->unbound(pin, "texture (it is bound to a buffer)");
    return ph.tex;
}

Buffer PassContext::buffer(const std::string& pin) const {
    const Binding* b = impl_->binding(pin);
    if (!b) impl_->unbound(pin, "buffer");
    const auto& ph = impl_->host.physical(b->resource, b->previous);
    if (!ph.buf) impl_->unbound(pin, "buffer (it is bound to a texture)");
    return ph.buf;
}

Buffer PassContext::grow_buffer(const std::string& pin, size_t bytes) {
    const Binding* b = impl_->binding(pin);
    if (!b) impl_->unbound(pin, "buffer");
    if (b->previous) throw PassError("pass '" + impl_->pass().name + "' cannot grow last frame's '" + pin + "'");
    auto& ph = impl_->host.physical(b->resource, false);
    if (!ph.buf) impl_->unbound(pin, "buffer (it is bound to a texture)");
    if (ph.buf.bytes >= bytes) return ph.buf;
    // A new, larger store: GL buffer storage is immutable. The content is not kept (a pass
    // grows a buffer it is about to refill); every pass that reads it sees the new one.
    GLuint id = 0;
    glCreateBuffers(1, &id);
    glNamedBufferStorage(id, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
    std::string label = impl_->host.graph().resources[size_t(b->resource)].name + " (grown)";
    glObjectLabel(GL_BUFFER, id, -1, label.c_str());
    glDeleteBuffers(1, &ph.buf.id);
    ph.buf = {id, bytes};
    // The pin's binding point and its view's unit now hold the new store (bind_pins bound the old one).
    if (const int at = impl_->bindings.buffer(pin); at >= 0) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(at), id);
    for (const bool image : {false, true}) {
        const auto& units = image ? impl_->bindings.image_pins() : impl_->bindings.sampler_pins();
        if (const auto u = units.find(pin); u != units.end()) impl_->bind_view_or_texture(pin, u->second, image);
    }
    return ph.buf;
}

const GpuScene& PassContext::scene() const { return impl_->host.scene(); }
const ShaderSource& PassContext::shaders() const { return impl_->shaders; }

ShaderProgram& PassContext::program(const std::vector<std::string>& files, const std::vector<std::string>& defines) {
    std::vector<ShaderStage> stages;
    for (const auto& f : files) {
        std::string file = impl_->shaders.find(f);  // the name is checked before its extension
        stages.push_back({ShaderStage::of_extension(f), {std::move(file)}});
    }
    return program_from(stages, defines);
}

ShaderProgram& PassContext::program_from(const std::vector<ShaderStage>& stages, const std::vector<std::string>& defines) {
    std::string key;
    for (const auto& s : stages) {
        key += std::to_string(s.stage) + ":";
        for (const auto& f : s.files) key += f + "+";
        key += "|";
    }
    key += "#";
    for (const auto& d : defines) key += d + "|";
    auto& slot = impl_->programs[key];
    if (!slot) {
        std::vector<std::string> all = defines;
        for (const auto& d : impl_->bindings.defines()) all.push_back(d);
        auto prog = std::make_unique<ShaderProgram>(ShaderProgram::build(stages, impl_->shaders, all));
        impl_->bindings.assign_units(*prog, *impl_->pass().type);
        // Uniform blocks keep the program's own numbering from 0 (ShaderProgram::block_binding).
        impl_->host.used(impl_->bindings, int(prog->uniform_blocks().size()));
        bind_params(*prog);
        slot = std::move(prog);
    }
    return *slot;
}

int PassContext::buffer_binding(const std::string& pin) const {
    const int point = impl_->bindings.buffer(pin);
    if (point < 0)
        throw PassError("pass '" + impl_->pass().name + "' asked for the binding point of '" + pin +
                        "', which is not one of its buffer pins");
    return point;
}

void PassContext::bind_params(const ShaderProgram& prog) const {
    PassBindings::bind_params(prog, *impl_->pass().type, impl_->params, pixel_scale());
}

GLuint PassContext::buffer_texture(const std::string& pin, GLenum format) {
    return impl_->buffer_views[{pin, format}].of(buffer(pin), format);
}

void PassContext::bind_framebuffer(const std::vector<std::string>& color_pins, const std::string& depth_pin, int mip) {
    std::vector<GLuint> color;
    int w = 0, h = 0;
    auto take_size = [&](const Texture& t) {
        w = std::max(1, t.width >> mip);
        h = std::max(1, t.height >> mip);
    };
    for (const auto& p : color_pins) {
        Texture t = texture(p);
        color.push_back(t.id);
        take_size(t);
    }
    GLuint depth = 0;
    if (!depth_pin.empty()) {
        Texture t = texture(depth_pin);
        depth = t.id;
        take_size(t);
    }
    if (color.empty() && !depth) {  // no attachments: the raster has the output's size
        w = std::max(1, output_size().x >> mip);
        h = std::max(1, output_size().y >> mip);
    }
    impl_->depth_bound = depth_pin;
    GLuint fbo = impl_->host.framebuffer(color, depth, mip, impl_->pass().name);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
}

std::string PassContext::write_image(const std::string& pin, const std::string& pattern) {
    // Through the render's output side: a pixel-pack copy now, encoded on a writer thread, the
    // file renamed into place once whole (Executor::finish() or the destructor waits for it).
    AsyncOutput::Capture c;
    c.what = "pass '" + pass_name() + "' input '" + pin + "'";
    c.tex = texture(pin);
    c.file = expand_pattern(pattern, {{"pass", pass_name()}}, frame_index());
    ensure_parent_dir(c.file);
    impl_->host.pass_output().capture({c});
    return c.file;
}

uint64_t PassContext::frame_index() const { return impl_->host.frame().index; }
double PassContext::time() const { return impl_->host.frame().time; }
const Camera& PassContext::camera() const { return impl_->host.frame().camera; }

void PassContext::frame_incomplete(uint64_t frame) { impl_->host.frame_incomplete(frame); }

void PassContext::stat(const std::string& name, double value) {
    impl_->host.stat(impl_->pass().name, name, value);
}

void PassContext::draw_fullscreen() {
    glBindVertexArray(impl_->host.empty_vertex_array());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}

void PassContext::draw_fullscreen(ShaderProgram& prog, glm::ivec4 rect, const std::string& depth_pin) {
    if (!depth_pin.empty() && depth_pin != impl_->depth_bound)
        throw std::logic_error("pass '" + pass_name() + "': draw_fullscreen on '" + depth_pin +
                               "' needs it bound as the framebuffer's depth (bind_framebuffer(..., \"" + depth_pin + "\"))");
    if (rect.z <= rect.x || rect.w <= rect.y) return;
    glEnable(GL_SCISSOR_TEST);
    glScissor(rect.x, rect.y, rect.z - rect.x, rect.w - rect.y);
    if (depth_pin.empty()) {
        prog.use();
        draw_fullscreen();
    } else {
        draw_fullscreen_on_geometry(prog);
    }
    glDisable(GL_SCISSOR_TEST);
}

void PassContext::draw_fullscreen_on_geometry(ShaderProgram& prog) {
    prog.use();
    prog.set("u_fullscreen_z", 1.0f);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);  // 1.0 > stored depth: geometry only
    glDepthMask(GL_FALSE);    // the depth texture stays read-only
    draw_fullscreen();
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
    prog.set("u_fullscreen_z", 0.0f);
}

}  // namespace pathlet
