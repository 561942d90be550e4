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
#include <pathlet/gl_limits.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

constexpr GLintptr kTargetGroupsAt = 4;    // OO_TARGET_GROUPS, in bytes
constexpr GLintptr kSegmentGroupsAt = 16;  // OO_SEGMENT_GROUPS, in bytes
constexpr double kStillStep = 1.0 / 25.0;  // seconds a frame without a time step counts as

class OpacityBlend : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override { prog_ = &ctx.program({"opacity_blend.comp"}); }

    void execute(pathlet::PassContext& ctx) override {
        const pathlet::Params& p = ctx.params();
        const pathlet::Buffer segments = ctx.buffer("segments"), targets = ctx.buffer("targets");
        const size_t bound = segments.bytes / 4;  // >= segments, >= header + line table
        pathlet::check_storage_block(8 * bound, "opacity_blend's state (8 bytes a segment)",
                                     "for " + std::to_string(bound) + " words of opacity_lists' segments",
                                     "a longer segment_length in opacity_lists makes fewer");
        ctx.grow_buffer("opacity", segments.bytes);
        ctx.grow_buffer("smooth_a", 4 * bound);
        ctx.grow_buffer("smooth_b", 4 * bound);
        // The state (kept across frames): a new store starts without any (generation 0).
        const pathlet::Buffer state = ctx.grow_buffer("state", 8 * bound);
        if (state.id != state_.id || state.bytes != state_.bytes) {
            const GLuint zero = 0;
            glClearNamedBufferData(state.id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
            state_ = state;
        }

        const double t = ctx.time();
        double dt = has_time_ ? std::fabs(t - last_time_) : 0.0;
        if (has_time_ && dt == 0.0) dt = kStillStep;
        const bool back = has_time_ && t < last_time_;
        last_time_ = t;
        const float half_life = p.f("half_life");
        const float blend = !has_time_ || back || half_life <= 0.0f ? 1.0f : float(1.0 - std::exp2(-dt / half_life));
        has_time_ = true;

        prog_->use();  // the pins, the pass's buffers and smoothing_rate by declaration
        prog_->set("u_blend", blend);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, targets.id);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        // Smoothing: the targets -> smooth_a -> smooth_b -> smooth_a ...; the blend reads the last.
        int from = 0;
        for (int k = 0; k < p.i("smoothing"); ++k) {
            phase(0, from);
            from = from == 1 ? 2 : 1;
        }
        phase(1, from);
        phase_on(2, from, segments.id, kSegmentGroupsAt);  // over the segments and the line table
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        ctx.stat("blend", blend);
    }

private:
    // One dispatch over the segments that got fragments (the targets' work groups).
    void phase(int which, int from) {
        prog_->set("u_phase", which);
        prog_->set("u_from", from);
        glDispatchComputeIndirect(kTargetGroupsAt);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    void phase_on(int which, int from, GLuint groups_buffer, GLintptr at) {
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, groups_buffer);
        prog_->set("u_phase", which);
        prog_->set("u_from", from);
        glDispatchComputeIndirect(at);
    }

    pathlet::ShaderProgram* prog_ = nullptr;
    pathlet::Buffer state_;  // the state store last seen (a new one is cleared)
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
                       "line pass's hook_buffer takes for optimized_fade.glsl",
                       {.bytes = 16})
        .internal_buffer("state", "per segment its opacity and the generation of the segmentation it belongs to",
                         {.bytes = 16}, {.persistent = true})
        .internal_buffer("smooth_a", "smoothing steps ping-pong between this and smooth_b", {.bytes = 16})
        .internal_buffer("smooth_b", "see smooth_a", {.bytes = 16})
        .make<OpacityBlend>();
}

}  // namespace

PATHLET_PLUGIN("opacity_blend", { sink->add(opacity_blend_type()); })
