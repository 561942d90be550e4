#include <pathlet/gpu_scene.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace pathlet {

namespace {
struct LineVertex {
    glm::vec3 position;
    float time;
    glm::vec3 velocity;
    glm::vec3 tangent;
    int32_t line_id;
    float arc;  // arc length from the line's first point
};
static_assert(sizeof(LineVertex) == GpuScene::kLineVertexBytes);
static_assert(sizeof(LineVertex) == GpuScene::kPointFloats * sizeof(float));
static_assert(offsetof(LineVertex, position) == GpuScene::kPositionFloat * sizeof(float));
static_assert(offsetof(LineVertex, time) == GpuScene::kTimeFloat * sizeof(float));

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

glm::vec3 safe_normalize(glm::vec3 v, glm::vec3 fallback) {
    float l = glm::length(v);
    return l > 1e-12f ? v / l : fallback;
}
}  // namespace

GpuScene::~GpuScene() { release(); }

void GpuScene::release() {
    if (line_vao_) glDeleteVertexArrays(1, &line_vao_);
    if (line_vbo_) glDeleteBuffers(1, &line_vbo_);
    if (points_tex_) glDeleteTextures(1, &points_tex_);
    if (chunk_buffer_) glDeleteBuffers(1, &chunk_buffer_);
    if (lod_buffer_) glDeleteBuffers(1, &lod_buffer_);
    if (position_buffer_) glDeleteBuffers(1, &position_buffer_);
    if (bundles_tex_) glDeleteTextures(1, &bundles_tex_);
    if (bundles_buffer_) glDeleteBuffers(1, &bundles_buffer_);
    mesh_.release();
    line_vao_ = line_vbo_ = points_tex_ = chunk_buffer_ = lod_buffer_ = position_buffer_ = bundles_buffer_ = bundles_tex_ = 0;
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

void GpuScene::upload(const Scene& scene) {
    release();
    cpu_ = &scene;
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

    // Interleave once; the tangent is the central difference (one-sided at the ends), so the
    // geometry shader gets smooth joins without adjacency primitives.
    std::vector<LineVertex> v(pl.position.size());
    arc_.assign(pl.position.size(), 0.0f);
    for (size_t li = 0; li < pl.lines.size(); ++li) {
        const LineRange r = pl.lines[li];
        double arc = 0.0;
        for (uint32_t k = 0; k < r.count; ++k) {
            size_t i = r.first + k;
            size_t a = r.first + (k > 0 ? k - 1 : 0), b = r.first + std::min(k + 1, r.count - 1);
            if (k > 0) {
                float step = glm::length(pl.position[i] - pl.position[i - 1]);
                if (std::isfinite(step)) arc += step;  // a bad point adds nothing, never NaN
            }
            arc_[i] = float(arc);
            glm::vec3 vel = i < pl.velocity.size() ? pl.velocity[i] : glm::vec3(0);
            v[i] = {pl.position[i], i < pl.time.size() ? pl.time[i] : 0.0f, vel,
                    safe_normalize(pl.position[b] - pl.position[a], glm::vec3(1, 0, 0)), int32_t(li), arc_[i]};
        }
    }
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
        static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
        position_buffer_ = immutable_buffer(pl.position.data(), pl.position.size() * sizeof(glm::vec3));
        std::vector<uint32_t> bundles(pl.lines.size());
        for (size_t li = 0; li < bundles.size(); ++li) bundles[li] = pl.bundle_of(li);
        bundles_buffer_ = immutable_buffer(bundles.data(), bundles.size() * sizeof(uint32_t));
        glCreateTextures(GL_TEXTURE_BUFFER, 1, &bundles_tex_);
        glTextureBuffer(bundles_tex_, GL_R32UI, bundles_buffer_);
    }
    glCreateBuffers(1, &line_vbo_);
    glNamedBufferStorage(line_vbo_, GLsizeiptr(std::max<size_t>(v.size(), 1) * sizeof(LineVertex)),
                         v.empty() ? nullptr : v.data(), 0);
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &points_tex_);
    glTextureBuffer(points_tex_, GL_R32F, line_vbo_);
    glCreateVertexArrays(1, &line_vao_);
    glVertexArrayVertexBuffer(line_vao_, 0, line_vbo_, 0, sizeof(LineVertex));
    auto attrib = [&](GLuint loc, GLint n, GLuint offset) {
        glEnableVertexArrayAttrib(line_vao_, loc);
        glVertexArrayAttribFormat(line_vao_, loc, n, GL_FLOAT, GL_FALSE, offset);
        glVertexArrayAttribBinding(line_vao_, loc, 0);
    };
    attrib(0, 3, offsetof(LineVertex, position));
    attrib(1, 1, offsetof(LineVertex, time));
    attrib(2, 3, offsetof(LineVertex, velocity));
    attrib(3, 3, offsetof(LineVertex, tangent));
    glEnableVertexArrayAttrib(line_vao_, 4);
    glVertexArrayAttribIFormat(line_vao_, 4, 1, GL_INT, offsetof(LineVertex, line_id));
    glVertexArrayAttribBinding(line_vao_, 4, 0);
    attrib(5, 1, offsetof(LineVertex, arc));

    if (scene.mesh && !scene.mesh->empty()) mesh_.upload(*scene.mesh);
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
