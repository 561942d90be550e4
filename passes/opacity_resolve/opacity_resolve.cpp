// opacity_resolve: opacity optimization, step 2. A compute shader over opacity_lists' lists
// (as many work groups as the lists ask for in their header: glDispatchComputeIndirect, so the
// resolution is said once, by opacity_lists) sorts every pixel's fragments and gives each
// segment the least opacity of the decoupled closed form over its fragments (Günther, Theisel,
// Gross 2017), for opacity_blend. The parameters q, r and lambda are the energy's.
//
// adapt = depth_complexity (default): q and r follow the data. A first dispatch over the same
// lists sums their fragments and covered pixels into the internal buffer `density`; the resolve
// reads the sums there (on the GPU: nothing waits) and scales q and r by
// (D / depth_reference)^adapt_exponent, D = fragments per covered pixel this frame. Sparse
// pictures clear less, dense ones more (docs/opacity-optimization.md: how it was found). The
// scale used is reported a frame or more late as the stats depth_complexity and clearing_scale.
#include <pathlet/gpu_readback.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

// The targets' header (shaders/opacity_optimization.glsl): count, blend work groups (x, 1, 1),
// peak, beyond, truncated, 0.
constexpr GLuint kTargetHeader[8] = {0, 0, 1, 1, 0, 0, 0, 0};
constexpr GLuint kUnseen = 0xFFFFFFFFu;  // OO_UNSEEN
// The density's words (opacity_resolve.comp): covered pixels and fragments (64 bits each), the
// scale of q and r the resolve used (float bits), one spare.
constexpr size_t kDensityWords = 6;

enum class Adapt { depth_complexity, fixed };

class OpacityResolve : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        // The pins' storage bindings come from the engine (LISTS_BINDING, SEGMENTS_BINDING, ...).
        const std::string k = "MAX_FRAGMENTS " + std::to_string(ctx.params().i("max_fragments"));
        prog_ = &ctx.program({"opacity_resolve.comp"}, {k});
        adapt_ = ctx.params().e<Adapt>("adapt") == Adapt::depth_complexity;
        measure_ = adapt_ ? &ctx.program({"opacity_resolve.comp"}, {k, "OO_MEASURE"}) : nullptr;
        if (!stats_) stats_ = std::make_unique<pathlet::GpuReadback>(sizeof seen_);
    }

    void execute(pathlet::PassContext& ctx) override {
        const pathlet::Buffer segments = ctx.buffer("segments"), lists = ctx.buffer("lists");
        // Two words per segment and the header; opacity_lists' segments buffer has at least one
        // word per segment beside its line table, so its size bounds the segment count (a bound
        // as tight as the buffer is the segments' own: the graph keeps it persistent, unpooled).
        const size_t bound = segments.bytes / 4;
        const size_t bytes = 4 * (8 + 2 * bound);
        const pathlet::Buffer targets = ctx.grow_buffer("targets", bytes);
        glClearNamedBufferSubData(targets.id, GL_R32UI, 0, GLsizeiptr(bytes), GL_RED_INTEGER, GL_UNSIGNED_INT, &kUnseen);
        glNamedBufferSubData(targets.id, 0, sizeof kTargetHeader, kTargetHeader);
        const pathlet::Buffer density = ctx.grow_buffer("density", 4 * kDensityWords);
        const GLuint zero = 0;
        glClearNamedBufferData(density.id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, lists.id);
        if (measure_) {  // the lists' depth complexity, summed on the GPU for the resolve below
            measure_->use();
            glDispatchComputeIndirect(0);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
        prog_->use();  // q, r, lambda, the adaptation and the pins by declaration
        glDispatchComputeIndirect(0);  // the lists' work groups (their header's first words)
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        // The statistics through a fenced copy, read when the GPU is done: the frame never waits.
        if (const void* p = stats_->poll_newest()) std::memcpy(seen_, p, sizeof seen_);
        stats_->copy(density.id, 0);
        const double pixels = double(seen_[0]) + 4294967296.0 * double(seen_[1]);
        const double fragments = double(seen_[2]) + 4294967296.0 * double(seen_[3]);
        float scale = 1.0f;
        std::memcpy(&scale, &seen_[4], 4);
        if (adapt_) ctx.stat("depth_complexity", pixels > 0 ? fragments / pixels : 0.0);
        ctx.stat("clearing_scale", seen_[4] ? double(scale) : 1.0);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    pathlet::ShaderProgram* measure_ = nullptr;  // adapt = depth_complexity only
    bool adapt_ = true;
    std::unique_ptr<pathlet::GpuReadback> stats_;
    GLuint seen_[kDensityWords] = {};  // the newest density known (a frame or more late)
};

pathlet::PassTypeInfo opacity_resolve_type() {
    return pathlet::PassTypeBuilder("opacity_resolve",
                                    "opacity optimization, step 2: per pixel of opacity_lists' lists, the fragments "
                                    "sorted and the decoupled closed form alpha = 1 / (1 + (1 - g)^(2 lambda) (r F + q "
                                    "B)); each segment keeps the least opacity of its fragments")
        .param_float("q", 10.0, 0.0, 100000.0,
                     "occlusion weight: how strongly a fragment clears for the squared importance behind it")
        .param_float("r", 0.5, 0.0, 100000.0,
                     "clutter weight: how strongly a fragment clears for the squared importance in front of it")
        .param_float("lambda", 2.0, 0.05, 20.0,
                     "importance shields itself: both penalties are scaled by (1 - importance)^(2 lambda)")
        .param_enum("adapt", "depth_complexity", {"depth_complexity", "fixed"},
                    "depth_complexity: q and r times (D / depth_reference)^adapt_exponent, D the frame's mean "
                    "fragments per covered pixel of the lists (measured on the GPU): sparse pictures clear less, "
                    "dense ones more; fixed: q and r as given")
        .param_float("depth_reference", 9.0, 0.01, 10000.0,
                     "adapt: the depth complexity at which q and r apply as given (9: the study phantom, about 3.3, "
                     "clears with 0.37 q and r)")
        .param_float("adapt_exponent", 1.0, 0.0, 8.0, "adapt: how steeply q and r follow the depth complexity")
        .param_float("adapt_min", 0.25, 0.0, 1000.0,
                     "adapt: the least factor of q and r (a very sparse picture still clears where focus is hidden)",
                     {.at_most = "adapt_max"})
        .param_float("adapt_max", 4.0, 0.0, 1000.0, "adapt: the largest factor of q and r")
        .param_int("max_fragments", 32, 1, 64,
                   "nearest fragments per pixel that get an opacity (all of them count as occluders); a longer list "
                   "is counted in the targets' header")
        .input_buffer("lists", "opacity_lists' per-pixel lists")
        .input_buffer("segments", "opacity_lists' segmentation")
        .output_buffer("targets",
                       "per segment the least opacity its fragments asked for (OO_UNSEEN: none), the segments that "
                       "got one, and the work groups opacity_blend needs (shaders/opacity_optimization.glsl)",
                       {.bytes = 32})
        .internal_buffer("density",
                         "adapt: the lists' covered pixels and fragments (64-bit sums) and the scale of q and r used "
                         "(opacity_resolve.comp); persistent only to be never pooled: 24 bytes a test can read",
                         {.bytes = 4 * kDensityWords}, {.persistent = true})
        .make<OpacityResolve>();
}

}  // namespace

PATHLET_PLUGIN("opacity_resolve", { sink->add(opacity_resolve_type()); })
