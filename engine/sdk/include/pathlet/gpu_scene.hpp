// The scene on the GPU: uploaded once, drawn per frame as per-line sub-ranges of the
// point buffer (a time window is a binary search per line on the CPU, then one
// glMultiDrawArrays; far cheaper on llvmpipe than discarding fragments by time).
#pragma once

#include <pathlet/gl.hpp>
#include <pathlet/line_chunks.hpp>
#include <pathlet/line_lod.hpp>
#include <pathlet/scene.hpp>

#include <algorithm>
#include <vector>

namespace pathlet {

// A triangle mesh on the GPU: location 0 position, 1 normal (interleaved), indexed; missing
// normals are computed. The scene's wall is one; a pass may upload its own (e.g. simplified).
class GpuMesh {
public:
    GpuMesh() = default;
    GpuMesh(const GpuMesh&) = delete;
    GpuMesh& operator=(const GpuMesh&) = delete;
    ~GpuMesh() { release(); }
    void upload(const Mesh& m);  // replaces what was there; needs a current GL context
    void release();
    GLuint vao() const { return vao_; }
    GLsizei index_count() const { return count_; }

private:
    GLuint vao_ = 0, vbo_ = 0, ibo_ = 0;
    GLsizei count_ = 0;
};

// Vertex layout of line_vao(): location 0 position (vec3), 1 time (float), 2 velocity (vec3),
// 3 tangent (vec3, unit, along the line), 4 line id (int, an integer attribute), 5 arc length
// from the line's first point (float, world units).
class GpuScene {
public:
    GpuScene() = default;
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;
    ~GpuScene();

    void upload(const Scene& scene);  // needs a current GL context
    const Scene& cpu() const { return *cpu_; }
    bool has_mesh() const { return mesh_.index_count() > 0; }

    GLuint line_vao() const { return line_vao_; }
    // The same points as a buffer texture of floats (R32F: samplerBuffer, texelFetch(t, i).r) for
    // compute passes: point i's position is at i * kPointFloats + kPositionFloat (3 floats), its
    // time at i * kPointFloats + kTimeFloat. Owned by the scene; bind it to a sampler of yours.
    GLuint points_texture() const { return points_tex_; }
    static constexpr int kPointFloats = 12, kPositionFloat = 0, kTimeFloat = 3;
    // The chunks, the level of detail and the points on the GPU, for the line kit's culling
    // (uploaded with the scene): per chunk {vec3 lo; uint first; vec3 hi; uint last; uint line;
    // 3 x uint} (std430, kGpuChunkBytes: its box, first and last point, line); per point its
    // LineLod tolerance (float) and its position (3 floats, packed). Apart from the vertices,
    // which at 48 bytes a point would pass the 128 MiB a storage block may be limited to (as on
    // llvmpipe) at 2.8M points: these reach it at 2.8M chunks and 11M points.
    static constexpr size_t kGpuChunkBytes = 48;
    GLuint chunk_buffer() const { return chunk_buffer_; }
    // Per line, its bundle (Pathlines::bundle_of) as a buffer texture of R32UI (usamplerBuffer,
    // texelFetch(t, line).r): the line kit's colormap=bundle reads it. 4 bytes a line.
    GLuint line_bundles_texture() const { return bundles_tex_; }
    GLuint lod_buffer() const { return lod_buffer_; }
    GLuint position_buffer() const { return position_buffer_; }
    GLuint mesh_vao() const { return mesh_.vao(); }  // location 0 position, 1 normal; indexed
    GLsizei mesh_index_count() const { return mesh_.index_count(); }

    // Per-line point ranges whose segments overlap [t0, t1] (a segment is kept when any
    // part of it lies in the window). window <= 0 means every line whole.
    struct Ranges {
        std::vector<GLint> first;
        std::vector<GLsizei> count;
        std::vector<uint32_t> line;  // line index of each range
        size_t segments = 0;
    };
    void ranges(double t0, double t1, Ranges& out) const;
    // Per line (indexed by line id), what the line kit's hooks measure from: arc length at the
    // pathlet's head and tail and the times that stand for age 0 and age 1. Windowed: the head
    // is t1 and the tail t0, clamped to the line for the arc lengths; whole lines (t1 <= t0):
    // the line's last and first points.
    void pathlets(double t0, double t1, std::vector<glm::vec4>& out) const;
    // Draws the ranges as GL_LINE_STRIPs with line_vao() bound (the caller binds a program).
    void draw_lines(const Ranges& r) const;

    // Level of detail of the lines (pathlet/line_lod.hpp), built at upload.
    const LineLod& lod() const { return lod_; }
    // The lines in chunks with bounding boxes (pathlet/line_chunks.hpp): what the kit culls.
    const LineChunks& chunks() const { return chunks_; }

    Bounds bounds() const { return bounds_; }
    // The line width passes use when theirs is 0 ("auto"): 0.5 % of the bounding-box
    // diagonal, about 3.5 px at 720p when the data fills the frame (1.1 mm on the phantom):
    // wide enough that a tube, its halo (>= 1 px per rim) and the AO between lines read at
    // the default framing.
    static float auto_line_width(const Bounds& b) {
        float d = b.valid() ? glm::length(b.hi - b.lo) : 0.0f;
        return d > 0.0f ? 0.005f * d : 1.0f;
    }
    float auto_line_width() const { return auto_line_width(bounds_); }
    // A pass's width: its line_width in world units when set (> 0), else the auto width times
    // its width_factor (a graph that wants wider lines says so relative to the data).
    float line_width(float param, float factor = 1.0f) const { return param > 0.0f ? param : factor * auto_line_width(); }
    // The widest line width any line pass has drawn this scene with (world units, before the
    // width hook, which is clamped to kMaxWidthHook): lines::screen_rect pads by it, so post
    // passes that skip the border never cut a wide line. Noted by lines::Drawer.
    static constexpr size_t kLineVertexBytes = 48;  // GPU memory per line point (the vertex buffer)
    static constexpr size_t kPointGpuBytes = kLineVertexBytes + 4 * sizeof(float);  // with its LOD tolerance and position for culling
    static constexpr float kMaxWidthHook = 4.0f;  // line_quad.geom's clamp (u_max_width_hook)
    void note_line_width(float w) const { widest_line_ = std::max(widest_line_, w); }
    float widest_line() const { return widest_line_; }
    float time_min() const { return tmin_; }
    float time_max() const { return tmax_; }
    // Robust speed range for colour maps: the 1st and 99th percentile of the point speeds
    // (Pathlines::speed_min/max give the true extremes).
    float speed_min() const { return smin_; }
    float speed_max() const { return smax_; }

private:
    void release();
    const Scene* cpu_ = nullptr;
    std::vector<float> arc_;  // per point, arc length from its line's first point
    LineLod lod_;
    LineChunks chunks_;
    GLuint line_vao_ = 0, line_vbo_ = 0, points_tex_ = 0, chunk_buffer_ = 0, lod_buffer_ = 0, position_buffer_ = 0;
    GLuint bundles_buffer_ = 0, bundles_tex_ = 0;
    GpuMesh mesh_;
    Bounds bounds_;
    float tmin_ = 0, tmax_ = 0, smin_ = 0, smax_ = 0;
    mutable float widest_line_ = 0;  // a record of use, not scene data
};

}  // namespace pathlet
