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

// The line points on the GPU, in two buffers (shaders/scene_points.glsl reads them):
// - points_buffer(): per point its position: quantised to 21 bits an axis in the lines'
//   bounding box, two words (PointLayout::quantised: at most 1/4194302 of the box's side off,
//   a few float steps), or 3 floats (PointLayout::exact, the default);
// - attributes_buffer(): per point its time (float), line id (int), speed and arc length from
//   the line's first point (world units): quantised, the speed as a half float and the arc in
//   16 bits of the longest line's (12 bytes); exact, floats (16 bytes). line_vao()'s attributes,
//   locations 0 (time), 1 (line id, an integer attribute), 2 (speed), 3 (arc), as floats.
// The tangent is not stored: the kit's vertex stage derives it from the neighbours (the central
// difference, one-sided at a line's ends), as the culling and the density read the same positions.
class ShaderProgram;
class GpuScene {
public:
    enum class PointLayout { quantised, exact };
    // PATHLET_POINT_LAYOUT=exact|quantised (default exact); anything else is an error naming it.
    static PointLayout default_point_layout();

    GpuScene() = default;
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;
    ~GpuScene();

    void upload(const Scene& scene, PointLayout layout = default_point_layout());  // needs a current GL context
    const Scene& cpu() const { return *cpu_; }
    bool has_mesh() const { return mesh_.index_count() > 0; }
    PointLayout point_layout() const { return layout_; }

    GLuint line_vao() const { return line_vao_; }
    GLuint points_buffer() const { return points_buffer_; }
    GLuint attributes_buffer() const { return attributes_buffer_; }
    // Binds the points to a program that includes scene_points.glsl: its samplers u_scene_points
    // (positions, RG32UI or RGB32UI) and u_scene_point_data (RGB32F or RGBA32F: time and line id
    // first), where declared, and the decoding's uniforms.
    void bind_points(const ShaderProgram& prog) const;
    // A point's position and arc length as the GPU decodes them, for tests and CPU checks.
    glm::vec4 stored_point(size_t point) const;

    // The chunks and the level of detail on the GPU, for the line kit's culling (uploaded with
    // the scene): per chunk {vec3 lo; uint first; vec3 hi; uint last; uint line; 3 x uint}
    // (std430, kGpuChunkBytes: its box, first and last point, line); per point its LineLod
    // tolerance (float). The culling reads the positions from points_buffer(). Storage blocks
    // may be limited to 128 MiB (as on llvmpipe): the quantised positions reach it at 16.7M
    // points, the tolerances at 33M, the chunks at 2.8M chunks.
    static constexpr size_t kGpuChunkBytes = 48;
    GLuint chunk_buffer() const { return chunk_buffer_; }
    // Per line, its bundle (Pathlines::bundle_of) as a buffer texture of R32UI (usamplerBuffer,
    // texelFetch(t, line).r): the line kit's colormap=bundle reads it. 4 bytes a line.
    GLuint line_bundles_texture() const { return bundles_tex_; }
    GLuint lod_buffer() const { return lod_buffer_; }

    // GPU memory of the line points, by buffer (what upload() allocates for them).
    struct PointMemory {
        size_t points = 0, chunks = 0;
        size_t positions = 0, attributes = 0, lod = 0, chunk_boxes = 0;  // bytes
        size_t total() const { return positions + attributes + lod + chunk_boxes; }
        double per_point() const { return points ? double(total()) / double(points) : 0.0; }
    };
    // For `points` points in `chunks` chunks (LineChunks) with a layout: what upload() allocates.
    static PointMemory point_memory(size_t points, size_t chunks, PointLayout layout);
    PointMemory point_memory() const { return point_memory(point_count_, chunks_.chunks().size(), layout_); }
    static const char* layout_name(PointLayout l) { return l == PointLayout::exact ? "exact" : "quantised"; }
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
    void upload_points(const Pathlines& pl);
    const Scene* cpu_ = nullptr;
    std::vector<float> arc_;  // per point, arc length from its line's first point
    LineLod lod_;
    LineChunks chunks_;
    GLuint line_vao_ = 0, points_buffer_ = 0, attributes_buffer_ = 0, points_tex_ = 0, attributes_tex_ = 0;
    GLuint chunk_buffer_ = 0, lod_buffer_ = 0;
    GLuint bundles_buffer_ = 0, bundles_tex_ = 0;
    GpuMesh mesh_;
    Bounds bounds_;
    PointLayout layout_ = PointLayout::exact;
    size_t point_count_ = 0;
    // Stored -> data: position origin + code * step; speed code * speed step; arc code * arc step.
    glm::vec3 points_origin_{0.0f}, points_step_{1.0f};
    float speed_step_ = 1.0f, arc_step_ = 1.0f;
    glm::uvec3 quantised(glm::vec3 position) const;
    float tmin_ = 0, tmax_ = 0, smin_ = 0, smax_ = 0;
    mutable float widest_line_ = 0;  // a record of use, not scene data
};

}  // namespace pathlet
