#include "chunk_culler.hpp"
#include "cull_scan.hpp"
#include "saved_bindings.hpp"

#include <pathlet/gl_limits.hpp>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <stdexcept>

namespace pathlet::lines {

namespace {

// Storage binding points of the culling stages (GLSL gets them as CULL_*_BINDING): eight, the
// GL 4.5 minimum of GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS; no stage uses more than six blocks.
enum Binding : GLuint { kChunks, kLod, kPositions, kLines, kState, kSlots, kIndices, kHeader, kBindings };
constexpr GLuint kTextureUnit = 0, kImageUnit = 0;  // the pyramid's sampler and image (saved, restored)
constexpr int kGroup = 64;          // invocations a work group (one a chunk)
constexpr int kTile = 4;            // pixels a side of a pyramid level-0 texel (8: 17 % more segments drawn)
constexpr int kTestTexels = 128;     // texels the depth test of a chunk reads at most
constexpr uint32_t kSlot = LineChunks::kSegments + 1;  // strip points a chunk's slot holds (see line_cull_chunks.comp)
constexpr size_t kStateBytes = 32;  // CullState in line_cull.glsl (checked against GL at first use)

using Header = CullHeader;  // cull_scan.hpp: the draw commands, the counts, the scan's scratch
constexpr size_t kCountsOffset = offsetof(Header, segments);
constexpr size_t kCountsBytes = sizeof(Header) - kCountsOffset;

std::string def(const char* name, size_t v) { return std::string(name) + " " + std::to_string(v); }

void dispatch(uint32_t invocations, uint32_t group) { glDispatchCompute(std::max<GLuint>(1, (invocations + group - 1) / group), 1, 1); }

// CullState's stride as GL lays it out against kStateBytes: a drift (an edited line_cull.glsl)
// is an error naming the struct, not chunks read from the wrong place.
void check_state_layout(const ShaderProgram& prog) {
    const GLuint i = glGetProgramResourceIndex(prog.id(), GL_BUFFER_VARIABLE, "cull_state[0].rect");
    GLint stride = -1;
    const GLenum prop = GL_TOP_LEVEL_ARRAY_STRIDE;
    if (i != GL_INVALID_INDEX) glGetProgramResourceiv(prog.id(), GL_BUFFER_VARIABLE, i, 1, &prop, 1, nullptr, &stride);
    if (stride != GLint(kStateBytes))
        throw ShaderError("line kit culling: CullState is " + std::to_string(stride) + " bytes in line_cull.glsl but " +
                          std::to_string(kStateBytes) + " in chunk_culler.cpp");
}

}  // namespace

size_t culling_bytes(size_t chunks, size_t segments) { return chunks * (kStateBytes + kSlot * 4) + segments * 2 * 4; }

const std::vector<std::string>& ChunkCuller::defines() {
    static const std::vector<std::string> d = [] {
        std::vector<std::string> v{def("CULL_CHUNKS_BINDING", kChunks),
            def("CULL_LOD_BINDING", kLod),
            def("CULL_POSITIONS_BINDING", kPositions),
            def("CULL_LINES_BINDING", kLines),
            def("CULL_STATE_BINDING", kState),
            def("CULL_SLOTS_BINDING", kSlots),
            def("CULL_INDICES_BINDING", kIndices),
            def("CULL_HEADER_BINDING", kHeader),
            def("CULL_GROUP", kGroup),
            def("CULL_TILE", kTile),
            def("CULL_TEST_TEXELS", kTestTexels),
            def("CULL_SLOT", kSlot),
            def("CULL_H_CMD", offsetof(Header, cmd) / 4),
            def("CULL_H_SEGMENTS", offsetof(Header, segments) / 4),
            def("CULL_H_CHUNKS", offsetof(Header, chunks) / 4),
            def("CULL_H_OUTSIDE", offsetof(Header, outside) / 4),
            def("CULL_H_DRAWN", offsetof(Header, drawn) / 4),
            def("CULL_H_OCCLUDED", offsetof(Header, occluded) / 4),
            def("CULL_H_SCRATCH", sizeof(Header) / 4)};
        for (std::string& x : CullScan::defines()) v.push_back(std::move(x));
        return v;
    }();
    return d;
}

ChunkCuller::~ChunkCuller() {
    GLuint buffers[] = {lines_, state_, slots_, indices_, header_};
    glDeleteBuffers(5, buffers);  // 0s are ignored
    if (pyramid_) glDeleteTextures(1, &pyramid_);
}

void ChunkCuller::allocate(const GpuScene& scene) {
    const std::vector<LineChunks::Chunk>& chunks = scene.chunks().chunks();
    const size_t segments = scene.chunks().segments();
    if (&scene == scene_ && chunks.size() == chunks_ && segments == segments_ && state_) return;
    GLuint old[] = {state_, slots_, indices_, header_};
    glDeleteBuffers(4, old);
    scene_ = &scene;
    chunks_ = chunks.size();
    segments_ = segments;
    // The scene's buffers the cull shaders read as storage blocks, and the indices they write,
    // against the block size (positions and indices grow with the data; the others less).
    const std::string at = "for " + std::to_string(scene.cpu().lines.position.size()) + " data points";
    check_storage_block(scene.cpu().lines.position.size() * sizeof(glm::vec3), "the line culling's positions", at,
                        "cull=false draws without it");
    check_storage_block(segments * 2 * 4, "the line culling's indices", at, "cull=false draws without it");
    // Zeroed state: nothing visible yet. A chunk's strip draws at most its own segment count
    // (line_cull_chunks.comp), so every segment of the scene twice (GL_LINES) bounds the indices.
    // (culling_bytes() adds these up.)
    std::vector<uint8_t> zero(std::max<size_t>(chunks_ * kStateBytes, 4), 0);
    glCreateBuffers(1, &state_);
    glNamedBufferStorage(state_, GLsizeiptr(zero.size()), zero.data(), 0);
    glCreateBuffers(1, &slots_);
    glNamedBufferStorage(slots_, GLsizeiptr(std::max<size_t>(chunks_ * kSlot * 4, 4)), nullptr, 0);
    glCreateBuffers(1, &indices_);
    glNamedBufferStorage(indices_, GLsizeiptr(std::max<size_t>(segments_ * 2 * 4, 4)), nullptr, 0);
    // The header's scratch grows with the chunks (the scan's block sums); copies in flight
    // from the old one are safe (GL deletes it once they are done).
    const std::vector<uint8_t> header(CullScan::header_bytes(chunks_), 0);
    glCreateBuffers(1, &header_);
    glNamedBufferStorage(header_, GLsizeiptr(header.size()), header.data(), 0);
    if (!counts_) counts_ = std::make_unique<GpuReadback>(kCountsBytes);
    fresh_ = true;
}

void ChunkCuller::upload_lines(const GpuScene& scene, const Frame& f) {
    const Pathlines& pl = scene.cpu().lines;
    const GpuScene::Ranges& w = *f.window;
    // Lines without a range: last < first.
    line_table_.assign(std::max<size_t>(pl.lines.size(), 1), glm::uvec4(1, 0, 0, 0));
    for (size_t i = 0; i < w.first.size(); ++i) {
        const uint32_t line = w.line[i];
        const float eps = f.lod ? scene.lod().tolerance(line, f.eye, f.scale, f.perspective, f.lod_px) : -1.0f;
        uint32_t bits;
        std::memcpy(&bits, &eps, sizeof bits);
        line_table_[line] = glm::uvec4(uint32_t(w.first[i]), uint32_t(w.first[i] + w.count[i] - 1), bits, pl.lines[line].first);
    }
    const size_t bytes = line_table_.size() * sizeof(glm::uvec4);
    if (bytes > lines_capacity_) {
        if (lines_) glDeleteBuffers(1, &lines_);
        glCreateBuffers(1, &lines_);
        glNamedBufferStorage(lines_, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
        lines_capacity_ = bytes;
    }
    glNamedBufferSubData(lines_, 0, GLsizeiptr(bytes), line_table_.data());
}

void ChunkCuller::bind_buffers(const GpuScene& scene) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kChunks, scene.chunk_buffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLod, scene.lod_buffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositions, scene.points_buffer());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLines, lines_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kState, state_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSlots, slots_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kIndices, indices_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kHeader, header_);
}

void ChunkCuller::scan_and_emit(PassContext& ctx, uint32_t chunks, int phase) {
    const std::vector<std::string>& d = defines();
    CullScan::run(ctx.program({"line_cull_scan.comp"}, d), header_, chunks, phase);
    ShaderProgram& emit = ctx.program({"line_cull_emit.comp"}, d);
    emit.use();
    set_uint(emit, "u_cull_chunks", chunks);
    emit.set("u_cull_phase", phase);
    dispatch(chunks, kGroup);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT);
}

// The depth after phase 1 as a pyramid of farthest depths (level 0: kTile x kTile pixels).
void ChunkCuller::pyramid(PassContext& ctx, GLuint depth, glm::ivec2 size) {
    const glm::ivec2 base = (size + kTile - 1) / kTile;
    if (base != pyramid_size_) {
        if (pyramid_) glDeleteTextures(1, &pyramid_);
        pyramid_levels_ = 1;
        for (int m = std::max(base.x, base.y); m > 1; m /= 2) ++pyramid_levels_;
        glCreateTextures(GL_TEXTURE_2D, 1, &pyramid_);
        glTextureStorage2D(pyramid_, pyramid_levels_, GL_R32F, base.x, base.y);
        pyramid_size_ = base;
    }
    const std::vector<std::string>& d = defines();
    static const std::vector<std::string> db = [] {
        std::vector<std::string> v = defines();
        v.push_back("CULL_PYRAMID_BASE");
        return v;
    }();
    glm::ivec2 level_size = base;
    for (int level = 0; level < pyramid_levels_; ++level) {
        ShaderProgram& p = ctx.program({"line_depth_pyramid.comp"}, level == 0 ? db : d);
        p.set_unit("u_cull_source", int(kTextureUnit));
        p.set_unit("u_cull_target", int(kImageUnit));
        p.use();
        if (level > 0) p.set("u_cull_level", level);
        glBindTextureUnit(kTextureUnit, level == 0 ? depth : pyramid_);
        glBindImageTexture(kImageUnit, pyramid_, level, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        glDispatchCompute(GLuint(level_size.x + 7) / 8, GLuint(level_size.y + 7) / 8, 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        level_size = glm::max(level_size / 2, glm::ivec2(1));
    }
}

void ChunkCuller::test(PassContext& ctx, glm::ivec2 size, uint32_t chunks, bool remember) {
    ShaderProgram& t = ctx.program({"line_cull_test.comp"}, defines());
    t.set_unit("u_cull_pyramid", int(kTextureUnit));
    t.use();
    set_uint(t, "u_cull_chunks", chunks);
    t.set("u_cull_pixels", size);
    t.set("u_cull_remember", remember ? 1 : 0);
    glBindTextureUnit(kTextureUnit, pyramid_);
    dispatch(chunks, kGroup);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void ChunkCuller::draw_phase(const GpuScene& scene, int phase) const {
    // The scene's VAO is shared by every line pass: bind this culler's indices each time.
    glVertexArrayElementBuffer(scene.line_vao(), indices_);
    glBindVertexArray(scene.line_vao());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, header_);
    glDrawElementsIndirect(GL_LINES, GL_UNSIGNED_INT, reinterpret_cast<const void*>(offsetof(Header, cmd) + size_t(phase - 1) * sizeof(Header::cmd[0])));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glBindVertexArray(0);
}

// This frame's counts, read back once the GPU is done (skipped while every copy is in flight).
void ChunkCuller::copy_counts() { counts_->copy(header_, kCountsOffset); }

bool ChunkCuller::stats(Stats& out) {
    const void* p = counts_ ? counts_->poll_newest() : nullptr;
    if (!p) return false;
    Header h{};
    std::memcpy(reinterpret_cast<char*>(&h) + kCountsOffset, p, kCountsBytes);
    out.chunks = h.chunks;
    out.frustum_culled = h.outside;
    out.phase1 = h.drawn[0];
    out.phase2 = h.drawn[1];
    out.occluded = h.occluded;
    out.segments = double(h.segments[0]) + double(h.segments[1]);
    return true;
}

void ChunkCuller::draw(PassContext& ctx, const ShaderProgram& prog, const Frame& f) {
    const GpuScene& scene = ctx.scene();
    allocate(scene);
    upload_lines(scene, f);
    const uint32_t chunks = uint32_t(chunks_);
    const bool two_phases = f.depth != 0;
    // The pyramid's texture and image units only where it is built (two phases).
    const SavedBindings saved(kBindings, two_phases ? kTextureUnit : SavedBindings::kNone,
                              two_phases ? kImageUnit : SavedBindings::kNone);
    bind_buffers(scene);

    ShaderProgram& c = ctx.program({"line_cull_chunks.comp"}, defines());
    if (&c != checked_) check_state_layout(c), checked_ = &c;
    c.use();
    scene.bind_points(c);
    c.set("u_cull_view_proj", f.view_proj);
    c.set("u_cull_grow", f.grow);
    set_uint(c, "u_cull_chunks", chunks);
    set_uint(c, "u_cull_points", uint32_t(scene.cpu().lines.position.size()));
    // max_skip as a mask (an integer division per point and lane is dear on llvmpipe).
    if (f.max_skip & (f.max_skip - 1)) throw std::logic_error("line kit culling: max_skip must be a power of two");
    set_uint(c, "u_cull_skip_mask", f.max_skip ? f.max_skip - 1 : ~0u);
    c.set("u_cull_occlusion", two_phases ? 1 : 0);
    dispatch(chunks, kGroup);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    scan_and_emit(ctx, chunks, 1);
    if (!two_phases) copy_counts();
    saved.restore();
    prog.use();
    draw_phase(scene, 1);
    if (two_phases) {
        bind_buffers(scene);
        pyramid(ctx, f.depth, f.depth_size);
            test(ctx, f.depth_size, chunks, false);
            scan_and_emit(ctx, chunks, 2);
            copy_counts();
        saved.restore();
        prog.use();
        draw_phase(scene, 2);
            if (fresh_) {  // phase 1 was empty: the final depth decides the next frame's
            bind_buffers(scene);
            pyramid(ctx, f.depth, f.depth_size);
            test(ctx, f.depth_size, chunks, true);
            saved.restore();
            prog.use();
        }
        fresh_ = false;
    }
}

}  // namespace pathlet::lines
