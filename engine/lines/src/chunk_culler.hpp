// The line kit's culling on the GPU (private to the kit; lines::Drawer uses it). Every line is
// cut at load into chunks of up to 8 segments with a box (pathlet/line_chunks.hpp, on the GPU
// as GpuScene::chunk_buffer()). Per frame the CPU uploads one entry per line (the time window's
// point range and the level of detail's tolerance) and records a fixed number of dispatches and
// two indirect draws; it never reads anything back or waits, and its work does not grow with the
// number of chunks:
//
//   chunks   (line_cull_chunks.comp, one invocation a chunk) the chunk's piece of the window,
//            its strip after the level of detail, the strip's box grown by the widest the line
//            can be drawn, the frustum test, and phase 1 = the chunks visible last frame;
//   scan     (line_cull_scan.comp) a prefix sum over the chunks in chunk order: where each
//            drawn chunk's segments go, the draw command, the counts;
//   emit     (line_cull_emit.comp) the segments as GL_LINES index pairs;
//   phase 1  glDrawElementsIndirect: one draw (llvmpipe pays ~5 us a draw, so a command per
//            chunk would cost more than the culling saves);
//   pyramid  (line_depth_pyramid.comp) the pass's depth after phase 1 as the farthest depth
//            per 4x4 tile, then 2x2 levels up to 1x1;
//   test     (line_cull_test.comp) every other chunk whose box lies behind every texel it
//            covers, at the finest level where that is at most 32 texels, is occluded; what the test does
//            not hide (phase 1's chunks too) is next frame's phase 1;
//   phase 2  scan, emit and draw of the chunks that became visible.
//
// Conservative, as the unculled draw is the reference: a chunk's box holds every point its
// strip draws (quads are clipped to the window inside the segments) grown by half the width
// times the width hook's cap, and a box reaching behind the camera is never hidden; a hidden
// chunk would have failed the depth test everywhere. The chunks' strips together are the
// unculled draw's strips, each segment once (line_cull_chunks.comp), in the same order within
// a phase, so OIT (every fragment counts) can be frustum-culled the same way.
//
// Counts (chunks drawn per phase, occluded, outside, segments) reach the CPU through a ring of
// fenced copies read once the GPU is done, without waiting: on llvmpipe in the same frame, on
// a GPU a frame or two late.
#pragma once

#include <pathlet/gpu_readback.hpp>
#include <pathlet/gpu_scene.hpp>
#include <pathlet/pass.hpp>
#include <pathlet/shader.hpp>

#include <memory>
#include <string>
#include <vector>

namespace pathlet::lines {

class ChunkCuller {
public:
    struct Stats {
        double chunks = 0;          // chunks with a segment in the window
        double frustum_culled = 0;  // ... outside the view
        double phase1 = 0, phase2 = 0, occluded = 0;
        double segments = 0;        // segments drawn (after the level of detail)
    };
    // What a frame culls: the window's per-line ranges, the level of detail as LineLod::select
    // takes it (lod_px <= 0 or no level of detail: every point), the camera, the width the
    // boxes grow by.
    struct Frame {
        const GpuScene::Ranges* window = nullptr;
        bool lod = false;
        glm::vec3 eye{0};
        float scale = 1, lod_px = 0;
        bool perspective = true;
        uint32_t max_skip = 0;  // LineLod::select's max_skip (0: none)
        glm::mat4 view_proj{1.0f};
        float grow = 0;
        GLuint depth = 0;       // the pass's depth texture: two phases around the depth test; 0: one
        glm::ivec2 depth_size{0};
    };

    ChunkCuller() = default;
    ChunkCuller(const ChunkCuller&) = delete;
    ChunkCuller& operator=(const ChunkCuller&) = delete;
    ~ChunkCuller();

    // Draws the frame's chunks with `prog` (in use, the kit's uniforms set): phase 1, and with
    // a depth texture the test and phase 2. GL state the pass set (buffer bindings, units,
    // program) is as it was for each draw and afterwards.
    void draw(PassContext& ctx, const ShaderProgram& prog, const Frame& f);

    // The newest counts the GPU has finished (false: none yet), read without waiting.
    bool stats(Stats& out);

    // GLSL defines every culling stage needs (binding points, chunk and slot length, layouts).
    static const std::vector<std::string>& defines();

private:
    void allocate(const GpuScene& scene);
    void upload_lines(const GpuScene& scene, const Frame& f);
    void bind_buffers(const GpuScene& scene) const;
    void scan_and_emit(PassContext& ctx, uint32_t chunks, int phase);
    void pyramid(PassContext& ctx, GLuint depth, glm::ivec2 size);
    void test(PassContext& ctx, glm::ivec2 size, uint32_t chunks, bool remember);
    void draw_phase(const GpuScene& scene, int phase) const;
    void copy_counts();

    const GpuScene* scene_ = nullptr;  // what the buffers were made for
    const ShaderProgram* checked_ = nullptr;  // the chunk stage whose CullState layout was checked
    size_t chunks_ = 0, segments_ = 0;
    bool fresh_ = true;  // no visibility yet: phase 1 is empty
    GLuint lines_ = 0, state_ = 0, slots_ = 0, indices_ = 0, header_ = 0;
    size_t lines_capacity_ = 0;
    std::vector<glm::uvec4> line_table_;
    GLuint pyramid_ = 0;
    glm::ivec2 pyramid_size_{0};
    int pyramid_levels_ = 0;

    std::unique_ptr<GpuReadback> counts_;  // the header's counts, read when the GPU is done
};

}  // namespace pathlet::lines
