// opacity_blend: opacity optimization, step 3 (compute). The least opacity opacity_resolve
// found per segment is smoothed along each line (smoothing Jacobi steps over the segments that
// got fragments, neighbours from the segmentation's line table), blended with the segment's
// state over time with a half-life in seconds of animation time (frame-rate independent), and
// published as `opacity`: the buffer a line pass's hook_buffer takes, read per fragment by
// shaders/oo_opacity.glsl between segment centres (the reference implementations interpolate per
// vertex; here every fragment interpolates at its own arc length).
//
// Time: dt is the change of the animation time since the last frame. A frame that does not move
// the clock (a paused viewer, a still rendered again) counts as kStillStep, so a frozen view
// still converges; a jump back (a loop) takes this frame's values.
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

// Storage bindings of the program, said once (OO_*_BINDING).
constexpr GLuint kSegments = 0, kTargets = 1, kSource = 2, kDest = 3, kState = 4, kOpacity = 5;
constexpr GLintptr kTargetGroupsAt = 4;    // OO_TARGET_GROUPS, in bytes
constexpr GLintptr kSegmentGroupsAt = 16;  // OO_SEGMENT_GROUPS, in bytes
constexpr GLuint kTargetAlphaAt = 8;       // OO_TARGET_ALPHA, in words
constexpr double kStillStep = 1.0 / 25.0;  // seconds a frame without a time step counts as

class OpacityBlend : public pathlet::Pass {
public:
    ~OpacityBlend() override {
        const GLuint b[3] = {state_, ping_[0], ping_[1]};
        glDeleteBuffers(3, b);
    }

    void setup(pathlet::PassContext& ctx) override {
        prog_ = &ctx.program({"opacity_blend.comp"},
                             {"OO_SEGMENTS_BINDING " + std::to_string(kSegments), "OO_TARGETS_BINDING " + std::to_string(kTargets),
                              "OO_SOURCE_BINDING " + std::to_string(kSource), "OO_DEST_BINDING " + std::to_string(kDest),
                              "OO_STATE_BINDING " + std::to_string(kState), "OO_OPACITY_BINDING " + std::to_string(kOpacity)});
    }

    void execute(pathlet::PassContext& ctx) override {
        const pathlet::Params& p = ctx.params();
        const pathlet::Buffer segments = ctx.buffer("segments"), targets = ctx.buffer("targets");
        const size_t bound = segments.bytes / 4;  // >= segments, >= header + line table
        ensure(bound);
        const pathlet::Buffer out = ctx.grow_buffer("opacity", segments.bytes);

        const double t = ctx.time();
        double dt = has_time_ ? std::fabs(t - last_time_) : 0.0;
        if (has_time_ && dt == 0.0) dt = kStillStep;
        const bool back = has_time_ && t < last_time_;
        last_time_ = t;
        const float half_life = p.f("half_life");
        const float blend = !has_time_ || back || half_life <= 0.0f ? 1.0f : float(1.0 - std::exp2(-dt / half_life));
        has_time_ = true;

        prog_->use();  // smoothing_rate by declaration
        prog_->set("u_blend", blend);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSegments, segments.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTargets, targets.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kState, state_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOpacity, out.id);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, targets.id);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
        // Smoothing: targets -> ping 0 -> ping 1 -> ...; then the blend reads the last.
        GLuint source = targets.id;
        GLuint source_at = kTargetAlphaAt;
        const int steps = p.i("smoothing");
        for (int k = 0; k < steps; ++k) {
            const GLuint dest = ping_[k % 2];
            phase(0, source, source_at, dest);
            source = dest;
            source_at = 0;
        }
        phase(1, source, source_at, 0);
        prog_->set("u_phase", 2);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, segments.id);
        glDispatchComputeIndirect(kSegmentGroupsAt);  // over the segments and the line table
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        ctx.stat("blend", blend);
    }

private:
    void phase(int which, GLuint source, GLuint source_at, GLuint dest) {
        prog_->set("u_phase", which);
        prog_->set("u_source_at", int(source_at));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSource, source);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDest, dest ? dest : ping_[0]);
        glDispatchComputeIndirect(kTargetGroupsAt);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }

    // Pass-private buffers for `bound` segments: the state (kept across frames, zero = no state)
    // and the two smoothing buffers.
    void ensure(size_t bound) {
        if (bound <= capacity_) return;
        const GLuint old[3] = {state_, ping_[0], ping_[1]};
        glDeleteBuffers(3, old);
        glCreateBuffers(1, &state_);
        glNamedBufferStorage(state_, GLsizeiptr(8 * bound), nullptr, GL_DYNAMIC_STORAGE_BIT);
        const GLuint zero = 0;
        glClearNamedBufferData(state_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glCreateBuffers(2, ping_);
        for (GLuint b : ping_) glNamedBufferStorage(b, GLsizeiptr(4 * bound), nullptr, 0);
        capacity_ = bound;
    }

    pathlet::ShaderProgram* prog_ = nullptr;
    GLuint state_ = 0, ping_[2] = {0, 0};
    size_t capacity_ = 0;
    double last_time_ = 0.0;
    bool has_time_ = false;
};

pathlet::PassTypeInfo opacity_blend_type() {
    return pathlet::PassTypeBuilder("opacity_blend",
                                    "opacity optimization, step 3: each segment's opacity smoothed along its line, "
                                    "blended over time with a half-life in seconds, published for the colour hooks "
                                    "(optimized_fade.glsl through a line pass's hook_buffer)")
        .param_int("smoothing", 15, 0, 100,
                   "Jacobi steps of the Laplacian along each line (the reference's default 15); 0 = none")
        .param_float("smoothing_rate", 0.5, 0.0, 1.0,
                     "how far one step moves a segment towards its neighbours' mean (variance ~ steps x rate / 2 "
                     "segments^2)")
        .param_float("half_life", 0.15, 0.0, 60.0,
                     "seconds of animation time over which a segment moves half-way to its new opacity (0: at once; "
                     "a frame that does not move the clock counts as 1/25 s)")
        .input_buffer("segments", "opacity_lists' segmentation")
        .input_buffer("targets", "opacity_resolve's least opacity per segment")
        .output_buffer("opacity",
                       "the segmentation's header and line table, then each segment's opacity (float): the buffer a "
                       "line pass's hook_buffer takes for optimized_fade.glsl / optimized_core.glsl",
                       {.bytes = 16})
        .make<OpacityBlend>();
}

}  // namespace

PATHLET_PLUGIN("opacity_blend", { sink->add(opacity_blend_type()); })
