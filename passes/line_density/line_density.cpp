// line_density: the line-density volume of the pathlets visible in the time window,
// rebuilt every frame: a grid of cubic voxels fitted to the lines' bounds (`grid` voxels along
// the longest side, two empty voxels of margin), cleared, then every segment of the window
// splatted by line_density.comp. The volume is a storage buffer (layout: the kit's
// line_density.glsl) that volume_ao, or a line pass through line_volume_ao.glsl, reads.
#include <pathlet/gl_limits.hpp>
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace lines = pathlet::lines;

// The memory cap: 2^26 voxels (256 MiB of cells). `grid` is at most 1024 by declaration; a grid
// whose fitted box exceeds the cap is an error in setup that names both.
constexpr size_t kMaxVoxels = size_t(1) << 26;
constexpr int kMargin = 2;  // empty voxels around the data: samples beyond the grid read zeros

size_t bytes_for(size_t voxels) { return lines::kDensityHeaderBytes + 4 * voxels; }

// The buffer the compiler allocates: the largest box `grid` can give (a cube), within the cap.
size_t bound_bytes(const pathlet::json& params) {
    const size_t n = size_t(params.at("grid").get<int>()) + 2 * kMargin;
    return bytes_for(std::min(n * n * n, kMaxVoxels));
}

struct Header {
    int dims[4];
    float origin[4];
    float info[4];
};
static_assert(sizeof(Header) == lines::kDensityHeaderBytes);

class LineDensity : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        // The points through the scene's buffer textures (GpuScene::bind_points, scene_points.glsl).
        prog_ = &ctx.program({"line_density.comp"}, lines::density_defines(ctx));
        // The grid: cubic voxels over the lines' bounds, the longest side cut into `grid`.
        const pathlet::Bounds b = ctx.scene().cpu().lines.bounds();
        const int grid = ctx.params().i("grid");
        const glm::vec3 lo = b.valid() ? b.lo : glm::vec3(0.0f), ext = b.valid() ? b.hi - b.lo : glm::vec3(0.0f);
        const float longest = std::max({ext.x, ext.y, ext.z});
        const float h = longest > 0.0f ? longest / float(grid) : 1.0f;
        size_t voxels = 1;
        for (int a = 0; a < 3; ++a) {
            dims_[a] = int(std::ceil(ext[a] / h - 1e-4f)) + 2 * kMargin;
            dims_[a] = std::max(dims_[a], 1 + 2 * kMargin);
            voxels *= size_t(dims_[a]);
        }
        if (voxels > kMaxVoxels)
            throw std::runtime_error("grid " + std::to_string(grid) + " over the lines' bounds needs " +
                                     std::to_string(dims_[0]) + " x " + std::to_string(dims_[1]) + " x " +
                                     std::to_string(dims_[2]) + " = " + std::to_string(voxels) + " voxels (" +
                                     std::to_string(bytes_for(voxels) >> 20) + " MiB), beyond the cap of " +
                                     std::to_string(kMaxVoxels) + " voxels (" + std::to_string(bytes_for(kMaxVoxels) >> 20) +
                                     " MiB); lower grid");
        pathlet::check_storage_block(bytes_for(voxels), "line_density's grid of " + std::to_string(voxels) + " voxels",
                                     "at grid " + std::to_string(grid), "lower grid");
        voxels_ = voxels;
        h_ = h;
        origin_ = lo - float(kMargin) * h;
        // The compiler allocated the bound; a --set that changed grid since then may need more.
        ctx.grow_buffer("density", bytes_for(voxels_));
        built_ = false;
    }

    void execute(pathlet::PassContext& ctx) override {
        const float step = ctx.params().f("time_step");
        // Time binning: the window's end snaps to a multiple of time_step, and the volume is
        // rebuilt only when it moves on (the resource must then be persistent).
        const double t = step > 0.0f ? std::floor(ctx.time() / double(step)) * double(step) : ctx.time();
        const lines::TimeWindow tw = lines::time_window(ctx.scene(), ctx.params().f("window"), t);  // as the kit draws
        const double t0 = tw.t0, t1 = tw.t1;
        const pathlet::Buffer buf = ctx.buffer("density");
        const bool same = built_ && step > 0.0f && buf.id == built_buffer_ && t0 == built_t0_ && t1 == built_t1_;
        ctx.stat("rebuilt", same ? 0.0 : 1.0);
        if (same) return;
        built_ = true;
        built_buffer_ = buf.id;
        built_t0_ = t0;
        built_t1_ = t1;
        const Header head{{dims_[0], dims_[1], dims_[2], 1},
                          {origin_.x, origin_.y, origin_.z, h_},
                          {float(t0), float(t1), 0.0f, 0.0f}};
        // The readers since the last rebuild (volume_ao, a list resolve) had the volume bound as
        // a storage block: their access lands before this update only behind the barrier.
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glNamedBufferSubData(buf.id, 0, sizeof head, &head);
        const GLuint zero = 0;
        glClearNamedBufferSubData(buf.id, GL_R32UI, GLintptr(sizeof head), GLsizeiptr(4 * voxels_), GL_RED_INTEGER,
                                  GL_UNSIGNED_INT, &zero);
        // One invocation per segment, given by its first point.
        ctx.scene().ranges(t0, t1, ranges_);
        starts_.clear();
        for (size_t k = 0; k < ranges_.first.size(); ++k)
            for (GLsizei i = 0; i + 1 < ranges_.count[k]; ++i) starts_.push_back(GLuint(ranges_.first[k] + i));
        if (!starts_.empty()) {
            // The engine's buffer, bound on SEGMENT_STARTS_BINDING by declaration (also when grown:
            // no per-frame allocation once the largest window has been seen).
            const size_t bytes = starts_.size() * sizeof(GLuint);
            pathlet::Buffer index = ctx.buffer("segment_starts");
            if (index.bytes < bytes) index = ctx.grow_buffer("segment_starts", bytes + bytes / 2);
            glNamedBufferSubData(index.id, 0, GLsizeiptr(bytes), starts_.data());
            prog_->use();
            prog_->set("u_segments", int(starts_.size()));
            prog_->set("u_window_range", glm::vec2(float(t0), float(t1)));
            prog_->set("u_windowed", tw.windowed ? 1 : 0);
            ctx.scene().bind_points(*prog_);
            glDispatchCompute(GLuint((starts_.size() + 63) / 64), 1, 1);
        }
        // Buffer update: the next rebuild's header write and clear (glNamedBufferSubData,
        // glClearNamedBufferSubData) must follow these atomics, whichever pass reads in between.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        ctx.stat("segments", double(starts_.size()));
        ctx.stat("voxels", double(voxels_));
        ctx.stat("volume_mib", double(bytes_for(voxels_)) / 1048576.0);
    }

private:
    bool built_ = false;  // time binning: what the buffer holds
    GLuint built_buffer_ = 0;
    double built_t0_ = 0, built_t1_ = 0;
    std::vector<GLuint> starts_;
    pathlet::ShaderProgram* prog_ = nullptr;
    pathlet::GpuScene::Ranges ranges_;
    int dims_[3] = {1, 1, 1};
    size_t voxels_ = 1;
    float h_ = 1.0f;
    glm::vec3 origin_{0.0f};
};

pathlet::PassTypeInfo line_density_type() {
    pathlet::PassTypeBuilder b("line_density",
                               "the line-density volume of the pathlets in the time window (pathlet length per voxel), "
                               "rebuilt every frame, for object-space AO (volume_ao, line_volume_ao.glsl)");
    lines::declare_window_param(b)
        .param_int("grid", 256, 8, 1024,
                   "voxels along the longest side of the lines' bounds (cubic voxels; at most 2^26 voxels in all, "
                   "256 MiB)")
        .param_float("time_step", 0.0, 0.0, 1e6,
                     "time binning in seconds: the window's end snaps down to a multiple of it and the volume is "
                     "rebuilt only when it moves on (declare the resource persistent); 0 = rebuilt every frame "
                     "for the exact window")
        .output_buffer("density",
                       "the volume: header and fixed-point cells (line_density.glsl); the compiler allocates the "
                       "largest box `grid` can give, the pass uses the part its data needs",
                       {.from_params = bound_bytes})
        .internal_buffer("segment_starts", "the first point of every segment in the window, one uint each (grown to "
                         "the largest window, kept across frames)", {.bytes = 4}, {.persistent = true});
    return b.make<LineDensity>();
}

}  // namespace

PATHLET_PLUGIN("line_density", { sink->add(line_density_type()); })
