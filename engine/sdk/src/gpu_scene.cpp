#include <pathlet/gpu_scene.hpp>
#include <pathlet/shader.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace pathlet {

namespace {
// attributes_buffer(): one RGB32F texel a point (scene_points.glsl: u_scene_point_data).
struct PointAttributes {
    float time;
    int32_t line_id;
    float speed;
};
static_assert(sizeof(PointAttributes) == 12);
// points_buffer(), quantised: RGBA16 (unorm) texels of x, y, z and the arc length; exact: RGBA32F.
size_t position_bytes(GpuScene::PointLayout l) { return 4 * (l == GpuScene::PointLayout::exact ? sizeof(float) : sizeof(uint16_t)); }

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

// The 16-bit code of x in [lo, lo + extent]: nearest, clamped (a non-finite x: 0).
uint16_t quantise(float x, float lo, float extent) {
    const float f = (x - lo) / extent * 65535.0f;
    return std::isfinite(f) ? uint16_t(std::clamp(std::lround(f), 0l, 65535l)) : 0;
}
}  // namespace

GpuScene::PointLayout GpuScene::default_point_layout() {
    const char* e = std::getenv("PATHLET_POINT_LAYOUT");
    if (!e || !*e || std::strcmp(e, "quantised") == 0) return PointLayout::quantised;
    if (std::strcmp(e, "exact") == 0) return PointLayout::exact;
    throw std::invalid_argument(std::string("PATHLET_POINT_LAYOUT='") + e + "': expected quantised or exact");
}

GpuScene::PointMemory GpuScene::point_memory(size_t points, size_t chunks, PointLayout layout) {
    PointMemory m;
    m.points = points;
    m.chunks = chunks;
    m.positions = points * position_bytes(layout);
    m.attributes = points * sizeof(PointAttributes);
    m.lod = points * sizeof(float);
    m.chunk_boxes = chunks * kGpuChunkBytes;
    return m;
}

GpuScene::~GpuScene() { release(); }

void GpuScene::release() {
    if (line_vao_) glDeleteVertexArrays(1, &line_vao_);
    const GLuint textures[] = {points_tex_, attributes_tex_};
    glDeleteTextures(2, textures);
    const GLuint buffers[] = {points_buffer_, attributes_buffer_, chunk_buffer_, lod_buffer_};
    glDeleteBuffers(4, buffers);
    mesh_.release();
    line_vao_ = points_buffer_ = attributes_buffer_ = points_tex_ = attributes_tex_ = chunk_buffer_ = lod_buffer_ = 0;
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
    }
    if (scene.mesh && !scene.mesh->empty()) mesh_.upload(*scene.mesh);
}

// The two point buffers, their buffer textures and the VAO over the attributes.
void GpuScene::upload_points(const Pathlines& pl) {
    point_count_ = pl.position.size();
    std::vector<PointAttributes> attr(pl.position.size());
    arc_.assign(pl.position.size(), 0.0f);
    for (size_t li = 0; li < pl.lines.size(); ++li) {
        const LineRange r = pl.lines[li];
        double arc = 0.0;
        for (uint32_t k = 0; k < r.count; ++k) {
            const size_t i = r.first + k;
            if (k > 0) {
                float step = glm::length(pl.position[i] - pl.position[i - 1]);
                if (std::isfinite(step)) arc += step;  // a bad point adds nothing, never NaN
            }
            arc_[i] = float(arc);
            const glm::vec3 vel = i < pl.velocity.size() ? pl.velocity[i] : glm::vec3(0);
            attr[i] = {i < pl.time.size() ? pl.time[i] : 0.0f, int32_t(li), glm::length(vel)};
        }
    }
    attributes_buffer_ = immutable_buffer(attr.data(), attr.size() * sizeof(PointAttributes));
    attr = {};

    // The box of the lines' finite points (not the scene's, which holds the wall too), and the
    // longest line's arc length.
    const Bounds b = pl.bounds();
    points_origin_ = glm::vec4(0.0f);
    points_extent_ = glm::vec4(1.0f);
    if (layout_ == PointLayout::exact) {
        std::vector<glm::vec4> p(pl.position.size());
        for (size_t i = 0; i < p.size(); ++i) p[i] = glm::vec4(pl.position[i], arc_[i]);
        points_buffer_ = immutable_buffer(p.data(), p.size() * sizeof(glm::vec4));
    } else {
        if (b.valid()) points_origin_ = glm::vec4(b.lo, 0.0f), points_extent_ = glm::vec4(b.hi - b.lo, 0.0f);
        points_extent_.w = arc_.empty() ? 0.0f : *std::max_element(arc_.begin(), arc_.end());
        points_extent_ = glm::max(points_extent_, glm::vec4(1e-30f));
        std::vector<Quantised> q(pl.position.size());
        static_assert(sizeof(Quantised) == 4 * sizeof(uint16_t));
        for (size_t i = 0; i < q.size(); ++i) q[i] = quantised(glm::vec4(pl.position[i], arc_[i]));
        points_buffer_ = immutable_buffer(q.data(), q.size() * sizeof(Quantised));
    }
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &points_tex_);
    glTextureBuffer(points_tex_, layout_ == PointLayout::exact ? GL_RGBA32F : GL_RGBA16, points_buffer_);
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &attributes_tex_);
    glTextureBuffer(attributes_tex_, GL_RGB32F, attributes_buffer_);

    glCreateVertexArrays(1, &line_vao_);
    glVertexArrayVertexBuffer(line_vao_, 0, attributes_buffer_, 0, sizeof(PointAttributes));
    auto attrib = [&](GLuint loc, GLuint offset) {
        glEnableVertexArrayAttrib(line_vao_, loc);
        glVertexArrayAttribFormat(line_vao_, loc, 1, GL_FLOAT, GL_FALSE, offset);
        glVertexArrayAttribBinding(line_vao_, loc, 0);
    };
    attrib(0, offsetof(PointAttributes, time));
    glEnableVertexArrayAttrib(line_vao_, 1);
    glVertexArrayAttribIFormat(line_vao_, 1, 1, GL_INT, offsetof(PointAttributes, line_id));
    glVertexArrayAttribBinding(line_vao_, 1, 0);
    attrib(2, offsetof(PointAttributes, speed));
}

GpuScene::Quantised GpuScene::quantised(glm::vec4 p) const {
    Quantised q;
    for (int a = 0; a < 4; ++a) q[a] = quantise(p[a], points_origin_[a], points_extent_[a]);
    return q;
}

glm::vec4 GpuScene::stored_point(size_t i) const {
    const glm::vec4 p(cpu_->lines.position[i], arc_[i]);
    if (layout_ == PointLayout::exact) return p;
    const Quantised q = quantised(p);
    return points_origin_ + glm::vec4(q[0], q[1], q[2], q[3]) / 65535.0f * points_extent_;
}

void GpuScene::bind_points(const ShaderProgram& prog) const {
    if (prog.declares("u_scene_points")) prog.bind_texture("u_scene_points", points_tex_);
    if (prog.declares("u_scene_point_data")) prog.bind_texture("u_scene_point_data", attributes_tex_);
    if (prog.declares("u_scene_points_origin")) prog.set("u_scene_points_origin", points_origin_);
    if (prog.declares("u_scene_points_extent")) prog.set("u_scene_points_extent", points_extent_);
    if (prog.declares("u_scene_points_quantised")) prog.set("u_scene_points_quantised", layout_ == PointLayout::quantised ? 1 : 0);
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
