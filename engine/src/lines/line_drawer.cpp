// The line kit's draw: programs of the kit's stages plus a pass's hooks, the shared uniforms,
// the per-pathlet buffer and the time-window draw.
#include <pathlet/lines.hpp>

#include <algorithm>

namespace pathlet::lines {

ShaderProgram& program(PassContext& ctx, const std::vector<std::string>& fragment, const Hooks& hooks,
                       const std::vector<std::string>& defines) {
    std::vector<std::string> files{"line_kit.vert", "line_quad.geom",
                                   hooks.width.empty() ? "line_width_default.geom" : hooks.width};
    files.insert(files.end(), fragment.begin(), fragment.end());
    files.push_back(hooks.color.empty() ? "line_color_default.frag" : hooks.color);
    return ctx.program(files, defines);
}

Drawer::~Drawer() {
    if (buffer_) glDeleteBuffers(1, &buffer_);
}

void Drawer::prepare(PassContext& ctx, const ShaderProgram& prog) {
    const Params& p = ctx.params();
    const Camera& cam = ctx.camera();
    const GpuScene& scene = ctx.scene();
    const float window = p.f("window");
    const bool windowed = window > 0.0f;
    const double t = ctx.time();
    // CPU sub-ranges per line: far cheaper on llvmpipe than culling in the GS or the FS.
    scene.ranges(windowed ? t - window : 0.0, windowed ? t : 0.0, ranges_);
    scene.pathlets(windowed ? t - window : 0.0, windowed ? t : 0.0, pathlets_);
    if (pathlets_.empty()) pathlets_.push_back(glm::vec4(0.0f));  // a buffer of size 0 cannot be bound
    // Grow-only: no per-frame allocation once the data set's line count is reached.
    size_t bytes = pathlets_.size() * sizeof(glm::vec4);
    if (bytes > capacity_) {
        if (buffer_) glDeleteBuffers(1, &buffer_);
        glCreateBuffers(1, &buffer_);
        glNamedBufferStorage(buffer_, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
        capacity_ = bytes;
    }
    glNamedBufferSubData(buffer_, 0, GLsizeiptr(bytes), pathlets_.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPathletBinding, buffer_);

    float smin = p.f("speed_min") > 0.0f ? p.f("speed_min") : scene.speed_min();
    float smax = p.f("speed_max") > 0.0f ? p.f("speed_max") : scene.speed_max();
    if (!(smax > smin)) smax = smin + 1.0f;
    prog.set("u_view", cam.view);
    prog.set("u_proj", cam.proj);
    prog.set("u_window", glm::vec2(float(t) - window, float(t)));
    prog.set("u_windowed", windowed ? 1 : 0);
    prog.set("u_half_width", 0.5f * scene.line_width(p.f("line_width")));
    prog.set("u_halo", p.f("halo"));
    prog.set("u_halo_depth", p.f("halo_depth"));
    prog.set("u_halo_color", p.v3("halo_color"));
    prog.set("u_depth_range", glm::vec2(cam.near_plane, cam.far_plane));
    prog.set("u_speed_range", glm::vec2(smin, smax));
    prog.set("u_colormap", colormap_index(p.s("colormap")));
}

void Drawer::draw(PassContext& ctx, const ShaderProgram& prog) {
    prepare(ctx, prog);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(depth_func_);  // LEQUAL: halos pushed past the far plane still land on the cleared 1.0
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);  // quads face either way
    ctx.scene().draw_lines(ranges_);
    glDisable(GL_DEPTH_TEST);
    ctx.stat("segments", double(ranges_.segments));
    ctx.stat("lines", double(ranges_.first.size()));
}

namespace {
GLuint bound_framebuffer() {
    GLint fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    return GLuint(fbo);
}
// Clear values go through the masks: open them all first.
void open_masks() {
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
}
}  // namespace

void clear_color(int index, glm::vec4 value) {
    open_masks();
    glClearNamedFramebufferfv(bound_framebuffer(), GL_COLOR, index, &value.x);
}

void clear_color_int(int index, glm::ivec4 value) {
    open_masks();
    glClearNamedFramebufferiv(bound_framebuffer(), GL_COLOR, index, &value.x);
}

void clear_depth(float value) {
    open_masks();
    glClearNamedFramebufferfv(bound_framebuffer(), GL_DEPTH, 0, &value);
}

}  // namespace pathlet::lines
