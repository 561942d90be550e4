// The line kit's draw: programs of the kit's stages plus a pass's hooks, the shared uniforms,
// the per-pathlet buffer and the time-window draw.
#include <pathlet/lines.hpp>

#include <algorithm>
#include <cmath>

#include <glm/matrix.hpp>

namespace pathlet::lines {

namespace {
// A program with a width hook (LINE_WIDTH_HOOKED) has the active uniform u_lod_max_skip: its
// geometry shader splits a drawn segment back into at most this many pieces (kMaxPieces in
// line_quad.geom), so the level of detail joins no more data segments than that.
constexpr uint32_t kWidthHookMaxSkip = 16;
}  // namespace

ShaderProgram& program(PassContext& ctx, const std::vector<std::string>& fragment, const Hooks& hooks,
                       const std::vector<std::string>& defines) {
    std::vector<std::string> files{"line_kit.vert", "line_quad.geom",
                                   hooks.width.empty() ? "line_width_default.geom" : hooks.width};
    files.insert(files.end(), fragment.begin(), fragment.end());
    files.push_back(hooks.color.empty() ? "line_color_default.frag" : hooks.color);
    std::vector<std::string> all = defines;
    if (!hooks.width.empty()) all.push_back("LINE_WIDTH_HOOKED");  // see line_quad.geom
    // Specialised per colour map and for the default (opaque) colour hook: llvmpipe runs both
    // sides of every branch, so a uniform switch costs all four maps per fragment. setup()
    // runs again when a parameter changes, which picks the new variant.
    if (ctx.params().raw().contains("colormap"))
        all.push_back("LINE_COLORMAP " + std::to_string(colormap_index(ctx.params().s("colormap"))));
    if (hooks.color.empty()) all.push_back("LINE_OPAQUE");
    return ctx.program(files, all);
}

Drawer::~Drawer() {
    if (buffer_) glDeleteBuffers(1, &buffer_);
    if (index_buffer_) glDeleteBuffers(1, &index_buffer_);
}

namespace {
// Grow-only buffer: no per-frame allocation once the largest frame has been seen.
void upload(GLuint& buffer, size_t& capacity, const void* data, size_t bytes) {
    if (bytes > capacity) {
        if (buffer) glDeleteBuffers(1, &buffer);
        glCreateBuffers(1, &buffer);
        capacity = std::max(bytes, capacity + capacity / 2);
        glNamedBufferStorage(buffer, GLsizeiptr(capacity), nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    if (bytes) glNamedBufferSubData(buffer, 0, GLsizeiptr(bytes), data);
}
}  // namespace

void Drawer::prepare(PassContext& ctx, const ShaderProgram& prog) {
    const Params& p = ctx.params();
    const Camera& cam = ctx.camera();
    const GpuScene& scene = ctx.scene();
    const float window = p.f("window");
    const bool windowed = window > 0.0f && !scene.cpu().lines.timeless;  // streamlines: whole
    const double t = ctx.time();
    // CPU sub-ranges per line: far cheaper on llvmpipe than culling in the GS or the FS.
    scene.ranges(windowed ? t - window : 0.0, windowed ? t : 0.0, ranges_);
    scene.pathlets(windowed ? t - window : 0.0, windowed ? t : 0.0, pathlets_);
    if (pathlets_.empty()) pathlets_.push_back(glm::vec4(0.0f));  // a buffer of size 0 cannot be bound
    upload(buffer_, capacity_, pathlets_.data(), pathlets_.size() * sizeof(glm::vec4));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPathletBinding, buffer_);

    // Level of detail: the pixel size in world units at distance d is scale * d (perspective)
    // or scale (orthographic), for the pass's output height.
    const float lod_px = p.f("lod") * ctx.pixel_scale();
    lod_on_ = lod_px > 0.0f && !scene.lod().empty();
    const bool width_hooked = prog.loc("u_lod_max_skip") >= 0;
    if (width_hooked) prog.set("u_lod_max_skip", int(kWidthHookMaxSkip));
    if (lod_on_) {
        const bool perspective = cam.proj[2][3] < -0.5f;
        const float scale =
            2.0f / (float(std::max(ctx.output_size().y, 1)) * std::max(std::fabs(cam.proj[1][1]), 1e-12f));
        const glm::vec3 eye = glm::vec3(glm::inverse(cam.view)[3]);
        const uint32_t max_skip = width_hooked ? kWidthHookMaxSkip : UINT32_MAX;
        scene.lod().select(ranges_.first, ranges_.count, ranges_.line, eye, scale, perspective, lod_px, strips_,
                           max_skip);
        upload(index_buffer_, index_capacity_, strips_.index.data(), strips_.index.size() * sizeof(GLuint));
    }

    float smin = p.f("speed_min") > 0.0f ? p.f("speed_min") : scene.speed_min();
    float smax = p.f("speed_max") > 0.0f ? p.f("speed_max") : scene.speed_max();
    if (!(smax > smin)) smax = smin + 1.0f;
    prog.set("u_view", cam.view);
    prog.set("u_proj", cam.proj);
    prog.set("u_window", glm::vec2(float(t) - window, float(t)));
    prog.set("u_windowed", windowed ? 1 : 0);
    width_ = scene.line_width(p.f("line_width"), p.f("width_factor"));
    scene.note_line_width(width_);
    prog.set("u_half_width", 0.5f * width_);
    prog.set("u_max_width_hook", GpuScene::kMaxWidthHook);
    prog.set("u_halo", p.f("halo"));
    prog.set("u_halo_min_px", p.f("halo_min_px") * ctx.pixel_scale());
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
    if (lod_on_) {
        if (!strips_.count.empty()) {
            // The scene's VAO is shared by every line pass: bind this drawer's indices each time.
            glVertexArrayElementBuffer(ctx.scene().line_vao(), index_buffer_);
            glBindVertexArray(ctx.scene().line_vao());
            glMultiDrawElements(GL_LINE_STRIP, strips_.count.data(), GL_UNSIGNED_INT, strips_.offset.data(),
                                GLsizei(strips_.count.size()));
            glBindVertexArray(0);
        }
    } else {
        ctx.scene().draw_lines(ranges_);
    }
    glDisable(GL_DEPTH_TEST);
    ctx.stat("segments", double(segments()));
    ctx.stat("segments_exact", double(ranges_.segments));  // before the level of detail
    ctx.stat("lines", double(ranges_.first.size()));
    ctx.stat("line_width", double(width_));  // world units, before the width hook (tests turn it into pixels)
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
