// The line kit's draw: programs of the kit's stages plus a pass's hooks, the shared uniforms,
// the per-pathlet buffer and the time-window draw.
#include <pathlet/lines.hpp>

#include "chunk_culler.hpp"

#include <algorithm>
#include <cstddef>
#include <cmath>

#include <glm/matrix.hpp>

namespace pathlet::lines {

namespace {
// A program with a width hook (LINE_WIDTH_HOOKED) has the active uniform u_lod_max_skip: its
// geometry shader splits a drawn segment back into at most this many pieces (kMaxPieces in
// line_quad.geom), so the level of detail joins no more data segments than that.
constexpr uint32_t kWidthHookMaxSkip = 16;
static_assert((kWidthHookMaxSkip & (kWidthHookMaxSkip - 1)) == 0, "the GPU culling keeps every max_skip-th point by a mask");

// The uniform block LineKit of line_common.glsl, std140: written whole once per draw.
struct KitBlock {
    glm::mat4 view, proj;
    glm::vec2 window, depth_range, speed_range;
    int32_t windowed;
    float half_width, max_width_hook, halo, halo_min_px, halo_depth;
    glm::vec3 halo_color;
    int32_t colormap;
    float typical_length;
    float pad_[3];  // std140 rounds the block to 16 bytes
};
static_assert(sizeof(KitBlock) == 208, "KitBlock must match LineKit's std140 size");

// The block's layout as GL sees it against KitBlock's, for every program the kit makes (a
// dozen queries, once per program): a drift between the two (an edited line_common.glsl on the
// shader path, a kit out of step) is an error naming the member, not wrong lines.
void check_block_layout(const ShaderProgram& prog) {
    const std::pair<const char*, size_t> members[] = {
        {"u_view", offsetof(KitBlock, view)},           {"u_proj", offsetof(KitBlock, proj)},
        {"u_window", offsetof(KitBlock, window)},       {"u_depth_range", offsetof(KitBlock, depth_range)},
        {"u_speed_range", offsetof(KitBlock, speed_range)}, {"u_windowed", offsetof(KitBlock, windowed)},
        {"u_half_width", offsetof(KitBlock, half_width)}, {"u_max_width_hook", offsetof(KitBlock, max_width_hook)},
        {"u_halo", offsetof(KitBlock, halo)},           {"u_halo_min_px", offsetof(KitBlock, halo_min_px)},
        {"u_halo_depth", offsetof(KitBlock, halo_depth)}, {"u_halo_color", offsetof(KitBlock, halo_color)},
        {"u_colormap", offsetof(KitBlock, colormap)},   {"u_typical_length", offsetof(KitBlock, typical_length)}};
    for (const auto& [name, offset] : members) {
        const GLuint i = glGetProgramResourceIndex(prog.id(), GL_UNIFORM, name);
        GLint at = -1;
        const GLenum prop = GL_OFFSET;
        if (i != GL_INVALID_INDEX) glGetProgramResourceiv(prog.id(), GL_UNIFORM, i, 1, &prop, 1, nullptr, &at);
        if (at != GLint(offset))
            throw ShaderError(std::string("line kit: member ") + name + " of the LineKit block is at offset " +
                              std::to_string(at) + " in GLSL but " + std::to_string(offset) +
                              " in lines::Drawer; line_common.glsl and line_drawer.cpp disagree");
    }
}
}  // namespace

Hooks hooks(const PassContext& ctx) {
    return {ctx.shaders().hook(HookRole::width), ctx.shaders().hook(HookRole::color)};
}

ShaderStage hook_stage(const ShaderSource& source, HookRole role, const std::string& file) {
    // A hook is only its function: compiled after the kit's definitions (LinePoint, the block).
    return {hook_role(role).stage, {source.find("line_hooks.glsl"), file}};
}

ShaderProgram& program(PassContext& ctx, const std::vector<std::string>& fragment, const Hooks& hooks,
                       const std::vector<std::string>& defines) {
    const ShaderSource& src = ctx.shaders();
    auto own = [&](const std::string& name) {
        std::string file = src.find(name);  // the name is checked before its extension
        return ShaderStage{ShaderStage::of_extension(name), {std::move(file)}};
    };
    std::vector<ShaderStage> stages{own("line_kit.vert"), own("line_quad.geom"),
                                    hooks.width.empty() ? own("line_width_default.geom")
                                                        : hook_stage(src, HookRole::width, hooks.width)};
    for (const auto& f : fragment) stages.push_back(own(f));
    stages.push_back(hooks.color.empty() ? own("line_color_default.frag") : hook_stage(src, HookRole::color, hooks.color));
    std::vector<std::string> all = defines;
    if (!hooks.width.empty()) all.push_back(hook_role(HookRole::width).defines);  // see line_quad.geom
    // Specialised per colour map and for the default (opaque) colour hook: llvmpipe runs both
    // sides of every branch, so a uniform switch costs all four maps per fragment. setup()
    // runs again when a parameter changes, which picks the new variant.
    if (ctx.params().raw().contains("colormap"))
        all.push_back("LINE_COLORMAP " + std::to_string(ctx.params().index("colormap")));
    if (hooks.color.empty()) all.push_back("LINE_OPAQUE");
    ShaderProgram& prog = ctx.program_from(stages, all);
    check_block_layout(prog);
    // A hook that reads the pass's hook_buffer (line_hook_buffer.glsl) needs it connected: else
    // the block would read whatever buffer was bound there last.
    if (!ctx.connected("hook_buffer") &&
        glGetProgramResourceIndex(prog.id(), GL_SHADER_STORAGE_BLOCK, "HookBuffer") != GL_INVALID_INDEX)
        throw ShaderError("a hook of " + ctx.pass_name() + " reads the buffer HookBuffer (line_hook_buffer.glsl), but the "
                          "pass's input 'hook_buffer' is not connected");
    return prog;
}

Drawer::Drawer() : culler_(std::make_unique<ChunkCuller>()) {}

Drawer::~Drawer() {
    if (block_) glDeleteBuffers(1, &block_);
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

void Drawer::begin(PassContext& ctx, const ShaderProgram& prog) {
    const Params& p = ctx.params();
    const Camera& cam = ctx.camera();
    const GpuScene& scene = ctx.scene();
    const float window = p.f("window");
    const TimeWindow tw = time_window(scene, window, ctx.time());
    const bool windowed = tw.windowed;
    // CPU sub-ranges per line: far cheaper on llvmpipe than culling in the GS or the FS.
    scene.ranges(tw.t0, tw.t1, ranges_);
    scene.pathlets(tw.t0, tw.t1, pathlets_);
    if (pathlets_.empty()) pathlets_.push_back(glm::vec4(0.0f));  // a buffer of size 0 cannot be bound
    upload(buffer_, capacity_, pathlets_.data(), pathlets_.size() * sizeof(glm::vec4));
    prog.bind_texture("u_line_pathlets", pathlets_view_.of({buffer_, capacity_}, GL_RGBA32F));
    if (prog.uniform("u_line_bundles")) prog.bind_texture("u_line_bundles", scene.line_bundles_texture());
    scene.bind_points(prog);

    // Level of detail: the pixel size in world units at distance d is scale * d (perspective)
    // or scale (orthographic), for the pass's output height.
    lod_.px = p.f("lod") * ctx.pixel_scale();
    lod_on_ = lod_.px > 0.0f && !scene.lod().empty();
    width_hooked_ = prog.loc("u_lod_max_skip") >= 0;
    if (width_hooked_) prog.set("u_lod_max_skip", int(kWidthHookMaxSkip));
    lod_.perspective = cam.proj[2][3] < -0.5f;
    lod_.scale = 2.0f / (float(std::max(ctx.output_size().y, 1)) * std::max(std::fabs(cam.proj[1][1]), 1e-12f));
    lod_.eye = glm::vec3(glm::inverse(cam.view)[3]);

    float smin = p.f("speed_min") > 0.0f ? p.f("speed_min") : scene.speed_min();
    float smax = p.f("speed_max") > 0.0f ? p.f("speed_max") : scene.speed_max();
    if (!(smax > smin)) smax = smin + 1.0f;
    width_ = line_width(ctx);
    scene.note_line_width(width_);
    const float typical_window = windowed ? window : 0.0f;  // streamlines (timeless) are drawn whole
    if (typical_window != typical_window_) {  // a median over the scene's points: when the window changes
        typical_length_ = typical_pathlet_length(scene.cpu(), typical_window);
        typical_window_ = typical_window;
    }
    const KitBlock block{cam.view,
                         cam.proj,
                         glm::vec2(float(ctx.time()) - window, float(ctx.time())),
                         glm::vec2(cam.near_plane, cam.far_plane),
                         glm::vec2(smin, smax),
                         windowed ? 1 : 0,
                         0.5f * width_,
                         GpuScene::kMaxWidthHook,
                         p.f("halo"),
                         p.f("halo_min_px") * ctx.pixel_scale(),
                         p.f("halo_depth"),
                         p.v3("halo_color"),
                         p.index("colormap"),
                         typical_length_,
                         {}};
    if (!block_) {
        glCreateBuffers(1, &block_);
        glNamedBufferStorage(block_, sizeof(KitBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    glNamedBufferSubData(block_, 0, sizeof(KitBlock), &block);
    if (prog.block_binding("LineKit") >= 0) glBindBufferBase(GL_UNIFORM_BUFFER, GLuint(prog.block_binding("LineKit")), block_);
    segments_ = 0;
}

void Drawer::select(const GpuScene& scene, const GpuScene::Ranges& r) {
    scene.lod().select(r.first, r.count, r.line, lod_.eye, lod_.scale, lod_.perspective, lod_.px, strips_,
                       width_hooked_ ? kWidthHookMaxSkip : UINT32_MAX);
    upload(index_buffer_, index_capacity_, strips_.index.data(), strips_.index.size() * sizeof(GLuint));
}

void Drawer::prepare(PassContext& ctx, const ShaderProgram& prog) {
    begin(ctx, prog);
    if (lod_on_) select(ctx.scene(), ranges_);
    segments_ = lod_on_ ? strips_.segments : ranges_.segments;
}

void Drawer::draw_ranges(PassContext& ctx, const GpuScene::Ranges& r) {
    if (r.first.empty()) return;
    if (!lod_on_) {
        ctx.scene().draw_lines(r);
        segments_ += r.segments;
        return;
    }
    select(ctx.scene(), r);
    const LineLod::Strips& s = strips_;
    segments_ += s.segments;
    if (s.count.empty()) return;
    // The scene's VAO is shared by every line pass: bind this drawer's indices each time.
    glVertexArrayElementBuffer(ctx.scene().line_vao(), index_buffer_);
    glBindVertexArray(ctx.scene().line_vao());
    glMultiDrawElements(GL_LINE_STRIP, s.count.data(), GL_UNSIGNED_INT, s.offset.data(), GLsizei(s.count.size()));
    glBindVertexArray(0);
}

namespace {
// The depth texture of the bound draw framebuffer (0: none) and its size.
GLuint bound_depth(glm::ivec2& size) {
    GLint fbo = 0, type = GL_NONE, name = 0, level = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    if (fbo == 0) return 0;
    glGetNamedFramebufferAttachmentParameteriv(GLuint(fbo), GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type != GL_TEXTURE) return 0;
    glGetNamedFramebufferAttachmentParameteriv(GLuint(fbo), GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
    glGetNamedFramebufferAttachmentParameteriv(GLuint(fbo), GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL, &level);
    if (level != 0) return 0;
    glGetTextureLevelParameteriv(GLuint(name), 0, GL_TEXTURE_WIDTH, &size.x);
    glGetTextureLevelParameteriv(GLuint(name), 0, GL_TEXTURE_HEIGHT, &size.y);
    return GLuint(name);
}
}  // namespace

void Drawer::draw(PassContext& ctx, const ShaderProgram& prog) {
    begin(ctx, prog);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(depth_func_);  // LEQUAL: halos pushed past the far plane still land on the cleared 1.0
    glDepthMask(GL_TRUE);
    if (!blending_) glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);  // quads face either way
    const GpuScene& scene = ctx.scene();
    // Culling pays from cull_min_segments data segments in the window; below, the plain draw.
    const bool cull = ctx.params().raw().value("cull", false) && !scene.chunks().chunks().empty() &&
                      ranges_.segments >= size_t(std::max(0, ctx.params().i("cull_min_segments")));
    if (!cull) {
        draw_ranges(ctx, ranges_);
    } else {
        const Camera& cam = ctx.camera();
        ChunkCuller::Frame f;
        f.window = &ranges_;
        f.lod = lod_on_;
        f.eye = lod_.eye;
        f.scale = lod_.scale;
        f.lod_px = lod_.px;
        f.perspective = lod_.perspective;
        f.max_skip = width_hooked_ ? kWidthHookMaxSkip : 0;
        f.view_proj = cam.proj * cam.view;
        // A box grows by the widest the line can be drawn: half the width, times the hook's cap.
        f.grow = 0.5f * width_ * (width_hooked_ ? GpuScene::kMaxWidthHook : 1.0f);
        // Only an opaque depth test hides anything: a pass that keeps every fragment (OIT's
        // depth ALWAYS, or occlusion culling switched off) gets the frustum test alone.
        if (occlusion_ && depth_func_ != GL_ALWAYS) f.depth = bound_depth(f.depth_size);
        // The newest counts the GPU has finished, asked before this frame's copy: polled right
        // after it, the new fence would be flushed mid-pass (a submit, a cache flush on some GPUs).
        ChunkCuller::Stats cs;
        const bool counted = culler_->stats(cs);
        culler_->draw(ctx, prog, f);
        if (counted) {
            ctx.stat("chunks", cs.chunks);
            ctx.stat("chunks_frustum_culled", cs.frustum_culled);
            ctx.stat("chunks_phase1", cs.phase1);
            ctx.stat("chunks_phase2", cs.phase2);
            ctx.stat("chunks_occluded", cs.occluded);
            ctx.stat("segments", cs.segments);
        }
    }
    if (!cull) ctx.stat("segments", double(segments_));
    ctx.stat("segments_exact", double(ranges_.segments));  // before culling and the level of detail
    ctx.stat("lines", double(ranges_.first.size()));
    ctx.stat("line_width", double(width_));  // world units, before the width hook (tests turn it into pixels)
}
namespace {
// Clear values go through the masks: open them all first.
void open_masks() {
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
}
}  // namespace

void clear_color(int index, glm::vec4 value) {
    open_masks();
    glClearBufferfv(GL_COLOR, index, &value.x);  // the bound draw framebuffer's, not asked for
}

void clear_color_int(int index, glm::ivec4 value) {
    open_masks();
    glClearBufferiv(GL_COLOR, index, &value.x);
}

void clear_depth(float value) {
    open_masks();
    glClearBufferfv(GL_DEPTH, 0, &value);
}

}  // namespace pathlet::lines
