#include <pathlet/gpu_scene.hpp>
#include <pathlet/shader.hpp>

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace pathlet {

namespace {
// attributes_buffer(), a texel (RGB32F / RGBA32F) and a vertex a point: time, line id, speed and
// arc length; quantised, the speed as a half float (of speed / speed step) and the arc length as
// 16 bits of the longest line's, in one word.
struct QuantisedAttributes {
    float time;
    int32_t line_id;
    uint16_t speed;
    uint16_t arc;
};
struct ExactAttributes {
    float time;
    int32_t line_id;
    float speed;
    float arc;
};
static_assert(sizeof(QuantisedAttributes) == 12 && sizeof(ExactAttributes) == 16);
// points_buffer(), quantised: two words a point, x, y, z of 21 bits each (RG32UI texels);
// exact: the floats' bits (RGB32UI).
constexpr uint32_t kAxisSteps = (1u << 21) - 1;
using PackedPosition = std::array<uint32_t, 2>;
size_t position_bytes(GpuScene::PointLayout l) { return l == GpuScene::PointLayout::exact ? 3 * sizeof(float) : sizeof(PackedPosition); }
size_t attribute_bytes(GpuScene::PointLayout l) {
    return l == GpuScene::PointLayout::exact ? sizeof(ExactAttributes) : sizeof(QuantisedAttributes);
}

// The code of x in steps of `step` from lo: nearest, clamped to [0, top] (a non-finite x: 0).
uint32_t quantise(float x, float lo, float step, uint32_t top) {
    const double f = (double(x) - double(lo)) / double(step);
    return std::isfinite(f) ? uint32_t(std::clamp(std::llround(f), 0ll, (long long)top)) : 0u;
}
PackedPosition pack(glm::uvec3 q) { return {q.x | (q.y << 21), (q.y >> 11) | (q.z << 10)}; }

// A chunk as GLSL's std430 struct {vec3 lo; uint first; vec3 hi; uint last; uint line; uvec3 pad;} lays it out.
struct GpuChunk {
    glm::vec3 lo;
    uint32_t first;
    glm::vec3 hi;
    uint32_t last;
    uint32_t line, pad[3];
};
static_assert(sizeof(GpuChunk) == GpuScene::kGpuChunkBytes);

// An immutable buffer with `data` (at least 4 bytes: a buffer of size 0 cannot be bound).
GLuint immutable_buffer(const void* data, size_t bytes) {
    GLuint b = 0;
    glCreateBuffers(1, &b);
    const uint32_t zero = 0;
    glNamedBufferStorage(b, GLsizeiptr(std::max<size_t>(bytes, sizeof zero)), bytes ? data : &zero, 0);
    return b;
}

}  // namespace

GpuScene::PointLayout GpuScene::default_point_layout() {
    const char* e = std::getenv("PATHLET_POINT_LAYOUT");
    // Exact by default: the quantised layout (30 bytes a point against 38) moves a few pixels by
    // more than 1/255 where lines cross at one depth, so it is the user's choice for large data.
    if (!e || !*e || std::strcmp(e, "exact") == 0) return PointLayout::exact;
    if (std::strcmp(e, "quantised") == 0) return PointLayout::quantised;
    throw std::invalid_argument(std::string("PATHLET_POINT_LAYOUT='") + e + "': expected quantised or exact");
}

GpuScene::PointMemory GpuScene::point_memory(size_t points, size_t chunks, PointLayout layout) {
    PointMemory m;
    m.points = points;
    m.chunks = chunks;
    m.positions = points * position_bytes(layout);
    m.attributes = points * attribute_bytes(layout);
    m.lod = points * sizeof(float);
    m.chunk_boxes = chunks * kGpuChunkBytes;
    return m;
}

GpuScene::~GpuScene() { release(); }

void GpuScene::release() {
    if (line_vao_) glDeleteVertexArrays(1, &line_vao_);
    const GLuint textures[] = {points_tex_, attributes_tex_, bundles_tex_};
    glDeleteTextures(3, textures);
    const GLuint buffers[] = {points_buffer_, attributes_buffer_, chunk_buffer_, lod_buffer_, bundles_buffer_};
    glDeleteBuffers(5, buffers);
    mesh_.release();
    line_vao_ = points_buffer_ = attributes_buffer_ = points_tex_ = attributes_tex_ = chunk_buffer_ = lod_buffer_ = 0;
    bundles_buffer_ = bundles_tex_ = 0;
    point_count_ = 0;
}

void GpuMesh::release() {
    if (vao_) glDeleteVertexArrays(1, &vao_);
    if (vbo_) glDeleteBuffers(1, &vbo_);
    if (ibo_) glDeleteBuffers(1, &ibo_);
    vao_ = vbo_ = ibo_ = 0;
    count_ = 0;
}

void GpuMesh::upload(const Mesh& mesh) {
    release();
    if (mesh.empty()) return;
    Mesh computed;
    const bool have_normals = mesh.normal.size() == mesh.position.size();
    if (!have_normals) computed = mesh, computed.compute_normals();
    const Mesh& m = have_normals ? mesh : computed;
    std::vector<float> interleaved;
    interleaved.reserve(m.position.size() * 6);
    for (size_t i = 0; i < m.position.size(); ++i) {
        interleaved.insert(interleaved.end(), {m.position[i].x, m.position[i].y, m.position[i].z});
        interleaved.insert(interleaved.end(), {m.normal[i].x, m.normal[i].y, m.normal[i].z});
    }
    glCreateBuffers(1, &vbo_);
    glNamedBufferStorage(vbo_, GLsizeiptr(interleaved.size() * sizeof(float)), interleaved.data(), 0);
    glCreateBuffers(1, &ibo_);
    glNamedBufferStorage(ibo_, GLsizeiptr(m.index.size() * sizeof(uint32_t)), m.index.data(), 0);
    glCreateVertexArrays(1, &vao_);
    glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, 6 * sizeof(float));
    glVertexArrayElementBuffer(vao_, ibo_);
    for (GLuint loc = 0; loc < 2; ++loc) {
        glEnableVertexArrayAttrib(vao_, loc);
        glVertexArrayAttribFormat(vao_, loc, 3, GL_FLOAT, GL_FALSE, loc * 3 * sizeof(float));
        glVertexArrayAttribBinding(vao_, loc, 0);
    }
    count_ = GLsizei(m.index.size());
}

void GpuScene::upload(const Scene& scene, PointLayout layout) {
    release();
    cpu_ = &scene;
    layout_ = layout;
    const Pathlines& pl = scene.lines;
    bounds_ = scene.bounds();
    tmin_ = pl.time_min();
    tmax_ = pl.time_max();
    // Colour range: 1st..99th percentile of the point speeds, so a few outliers (a particle
    // stuck near the wall, a spike in measured data) do not squash every line into one hue.
    {
        std::vector<float> sp;
        sp.reserve(pl.velocity.size());
        for (const auto& v : pl.velocity) {
            float s = glm::length(v);
            if (std::isfinite(s)) sp.push_back(s);
        }
        if (sp.empty()) {
            smin_ = smax_ = 0.0f;
        } else {
            auto pick = [&](double q) {
                size_t k = size_t(q * double(sp.size() - 1));
                std::nth_element(sp.begin(), sp.begin() + long(k), sp.end());
                return sp[k];
            };
            smin_ = pick(0.01);
            smax_ = pick(0.99);
            if (!(smax_ > smin_)) smin_ = pl.speed_min(), smax_ = pl.speed_max();
            // Streamlines have one pseudo-speed: the middle of the map for all, not noise from
            // its last bits.
            if (pl.timeless) smin_ = 0.0f, smax_ = 2.0f * pick(0.5);
        }
    }

    upload_points(pl);
    lod_.build(pl, smax_ - smin_);
    chunks_.build(pl);
    {
        std::vector<GpuChunk> gc;
        gc.reserve(chunks_.chunks().size());
        for (uint32_t line = 0; line < uint32_t(pl.lines.size()); ++line)
            for (uint32_t k = chunks_.begin(line); k < chunks_.end(line); ++k) {
                const LineChunks::Chunk& c = chunks_.chunks()[k];
                gc.push_back({c.box.lo, c.first, c.box.hi, c.last, line, {0, 0, 0}});
            }
        chunk_buffer_ = immutable_buffer(gc.data(), gc.size() * sizeof(GpuChunk));
        lod_buffer_ = immutable_buffer(lod_.keep().data(), lod_.keep().size() * sizeof(float));
        std::vector<uint32_t> bundles(pl.lines.size());
        for (size_t li = 0; li < bundles.size(); ++li) bundles[li] = pl.bundle_of(li);
        bundles_buffer_ = immutable_buffer(bundles.data(), bundles.size() * sizeof(uint32_t));
        glCreateTextures(GL_TEXTURE_BUFFER, 1, &bundles_tex_);
        glTextureBuffer(bundles_tex_, GL_R32UI, bundles_buffer_);
    }
    if (scene.mesh && !scene.mesh->empty()) mesh_.upload(*scene.mesh);
}

// The two point buffers, their buffer textures and the VAO over the attributes.
void GpuScene::upload_points(const Pathlines& pl) {
    point_count_ = pl.position.size();
    const bool exact = layout_ == PointLayout::exact;
    std::vector<float> speed(pl.position.size(), 0.0f);
    arc_.assign(pl.position.size(), 0.0f);
    float longest = 0.0f, fastest = 0.0f;
    for (const LineRange& r : pl.lines) {
        double arc = 0.0;
        for (uint32_t k = 0; k < r.count; ++k) {
            const size_t i = r.first + k;
            if (k > 0) {
                float step = glm::length(pl.position[i] - pl.position[i - 1]);
                if (std::isfinite(step)) arc += step;  // a bad point adds nothing, never NaN
            }
            arc_[i] = float(arc);
            speed[i] = i < pl.velocity.size() ? glm::length(pl.velocity[i]) : 0.0f;
            longest = std::max(longest, arc_[i]);
            if (std::isfinite(speed[i])) fastest = std::max(fastest, speed[i]);
        }
    }
    // Steps: the lines' box (not the scene's, which holds the wall too) in 2^21 - 1, the longest
    // line's arc length in 65535; the speed a half float, scaled by a power of two beyond 32768.
    const Bounds b = pl.bounds();
    points_origin_ = glm::vec3(0.0f);
    points_step_ = glm::vec3(1.0f);
    arc_step_ = speed_step_ = 1.0f;
    if (!exact) {
        if (b.valid()) points_origin_ = b.lo, points_step_ = glm::max((b.hi - b.lo) / float(kAxisSteps), glm::vec3(1e-30f));
        arc_step_ = std::max(longest / 65535.0f, 1e-30f);
        while (fastest / speed_step_ > 32768.0f) speed_step_ *= 2.0f;
    }
    const auto time_of = [&](size_t i) { return i < pl.time.size() ? pl.time[i] : 0.0f; };
    std::vector<int32_t> line_of(pl.position.size(), 0);
    for (size_t li = 0; li < pl.lines.size(); ++li)
        std::fill_n(line_of.begin() + pl.lines[li].first, pl.lines[li].count, int32_t(li));
    if (exact) {
        std::vector<ExactAttributes> attr(pl.position.size());
        for (size_t i = 0; i < attr.size(); ++i) attr[i] = {time_of(i), line_of[i], speed[i], arc_[i]};
        attributes_buffer_ = immutable_buffer(attr.data(), attr.size() * sizeof(ExactAttributes));
        static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
        points_buffer_ = immutable_buffer(pl.position.data(), pl.position.size() * sizeof(glm::vec3));
    } else {
        std::vector<QuantisedAttributes> attr(pl.position.size());
        for (size_t i = 0; i < attr.size(); ++i)
            attr[i] = {time_of(i), line_of[i], uint16_t(glm::packHalf1x16(speed[i] / speed_step_)),
                       uint16_t(quantise(arc_[i], 0.0f, arc_step_, 65535))};
        attributes_buffer_ = immutable_buffer(attr.data(), attr.size() * sizeof(QuantisedAttributes));
        std::vector<PackedPosition> q(pl.position.size());
        for (size_t i = 0; i < q.size(); ++i) q[i] = pack(quantised(pl.position[i]));
        points_buffer_ = immutable_buffer(q.data(), q.size() * sizeof(PackedPosition));
    }
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &points_tex_);
    glTextureBuffer(points_tex_, exact ? GL_RGB32UI : GL_RG32UI, points_buffer_);
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &attributes_tex_);
    glTextureBuffer(attributes_tex_, exact ? GL_RGBA32F : GL_RGB32F, attributes_buffer_);

    glCreateVertexArrays(1, &line_vao_);
    glVertexArrayVertexBuffer(line_vao_, 0, attributes_buffer_, 0, GLsizei(attribute_bytes(layout_)));
    auto attrib = [&](GLuint loc, GLenum type, GLboolean normalized, GLuint offset) {
        glEnableVertexArrayAttrib(line_vao_, loc);
        glVertexArrayAttribFormat(line_vao_, loc, 1, type, normalized, offset);
        glVertexArrayAttribBinding(line_vao_, loc, 0);
    };
    attrib(0, GL_FLOAT, GL_FALSE, offsetof(ExactAttributes, time));
    glEnableVertexArrayAttrib(line_vao_, 1);
    glVertexArrayAttribIFormat(line_vao_, 1, 1, GL_INT, offsetof(ExactAttributes, line_id));
    glVertexArrayAttribBinding(line_vao_, 1, 0);
    if (exact) {
        attrib(2, GL_FLOAT, GL_FALSE, offsetof(ExactAttributes, speed));
        attrib(3, GL_FLOAT, GL_FALSE, offsetof(ExactAttributes, arc));
    } else {
        attrib(2, GL_HALF_FLOAT, GL_FALSE, offsetof(QuantisedAttributes, speed));
        attrib(3, GL_UNSIGNED_SHORT, GL_TRUE, offsetof(QuantisedAttributes, arc));
    }
}

glm::uvec3 GpuScene::quantised(glm::vec3 p) const {
    glm::uvec3 q;
    for (int a = 0; a < 3; ++a) q[a] = quantise(p[a], points_origin_[a], points_step_[a], kAxisSteps);
    return q;
}

glm::vec4 GpuScene::stored_point(size_t i) const {
    const glm::vec3 p = cpu_->lines.position[i];
    if (layout_ == PointLayout::exact) return glm::vec4(p, arc_[i]);
    const float arc = float(quantise(arc_[i], 0.0f, arc_step_, 65535)) * arc_step_;
    return glm::vec4(points_origin_ + glm::vec3(quantised(p)) * points_step_, arc);
}

void GpuScene::bind_points(const ShaderProgram& prog) const {
    if (prog.declares("u_scene_points")) prog.bind_texture("u_scene_points", points_tex_);
    if (prog.declares("u_scene_point_data")) prog.bind_texture("u_scene_point_data", attributes_tex_);
    if (prog.declares("u_scene_points_origin")) prog.set("u_scene_points_origin", points_origin_);
    if (prog.declares("u_scene_points_step")) prog.set("u_scene_points_step", points_step_);
    if (prog.declares("u_scene_points_quantised")) prog.set("u_scene_points_quantised", layout_ == PointLayout::quantised ? 1 : 0);
    // The arc attribute arrives normalised (0..1 of 65535 steps) when quantised, as it is when exact.
    const float arc_scale = layout_ == PointLayout::quantised ? arc_step_ * 65535.0f : 1.0f;
    if (prog.declares("u_scene_point_scale")) prog.set("u_scene_point_scale", glm::vec2(speed_step_, arc_scale));
}

void GpuScene::ranges(double t0, double t1, Ranges& out) const {
    out.first.clear();
    out.count.clear();
    out.line.clear();
    out.segments = 0;
    if (!cpu_) return;
    const Pathlines& pl = cpu_->lines;
    bool whole = !(t1 > t0);
    for (size_t li = 0; li < pl.lines.size(); ++li) {
        const LineRange r = pl.lines[li];
        if (r.count < 2) continue;
        uint32_t a = 0, b = r.count;  // point indices [a, b) within the line
        if (!whole) {
            const float* t = pl.time.data() + r.first;
            // A segment [k, k+1] overlaps the window when t[k+1] >= t0 and t[k] <= t1.
            uint32_t lo = uint32_t(std::lower_bound(t, t + r.count, float(t0)) - t);  // first t >= t0
            uint32_t hi = uint32_t(std::upper_bound(t, t + r.count, float(t1)) - t);  // first t > t1
            a = lo > 0 ? lo - 1 : 0;
            b = std::min(hi + 1, r.count);
            if (lo >= r.count || hi == 0 || b <= a + 1) continue;
        }
        out.first.push_back(GLint(r.first + a));
        out.count.push_back(GLsizei(b - a));
        out.line.push_back(uint32_t(li));
        out.segments += b - a - 1;
    }
}

void GpuScene::pathlets(double t0, double t1, std::vector<glm::vec4>& out) const {
    out.clear();
    if (!cpu_) return;
    const Pathlines& pl = cpu_->lines;
    const bool whole = !(t1 > t0);
    out.resize(pl.lines.size(), glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));
    for (size_t li = 0; li < pl.lines.size(); ++li) {
        const LineRange r = pl.lines[li];
        if (r.count < 1 || pl.time.size() < size_t(r.first) + r.count) continue;
        const float* t = pl.time.data() + r.first;
        const float* s = arc_.data() + r.first;
        // Arc length at time x, linear between points, clamped to the line's ends.
        auto arc_at = [&](double x) {
            if (x <= t[0]) return s[0];
            if (x >= t[r.count - 1]) return s[r.count - 1];
            uint32_t k = uint32_t(std::upper_bound(t, t + r.count, float(x)) - t);  // t[k-1] <= x < t[k]
            double dt = double(t[k]) - double(t[k - 1]);
            double f = dt > 1e-12 ? (x - t[k - 1]) / dt : 1.0;
            return float(s[k - 1] + f * (s[k] - s[k - 1]));
        };
        if (whole)
            out[li] = {s[r.count - 1], s[0], t[r.count - 1], t[0]};
        else
            out[li] = {arc_at(t1), arc_at(t0), float(t1), float(t0)};
    }
}

void GpuScene::draw_lines(const Ranges& r) const {
    if (r.first.empty()) return;
    glBindVertexArray(line_vao_);
    glMultiDrawArrays(GL_LINE_STRIP, r.first.data(), r.count.data(), GLsizei(r.first.size()));
    glBindVertexArray(0);
}

}  // namespace pathlet
