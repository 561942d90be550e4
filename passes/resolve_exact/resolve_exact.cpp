// resolve_exact: the exact reference of the list techniques. Like resolve_list it composites
// each pixel's linked list front to back, but with every fragment: no cap on the list (a bounded
// block sorted in rounds, resolve_exact.frag), termination only when the transmittance left is
// below min_transmittance (1e-4), the fragments at one depth one layer (oit_depth_group.glsl, as
// depth_peel). With fill_list's never_drop the lists hold every fragment, so the picture is
// exact by construction; a pixel whose walk was cut anyway (a corrupt list, a driver's loop
// limit) makes its frame incomplete. The pass reports what it needed (peak list length, rounds).
#include <pathlet/gpu_readback.hpp>
#include <pathlet/lines.hpp>
#include <pathlet/oit.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

class ResolveExact : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        std::vector<std::string> defines = pathlet::oit::defines();
        defines.push_back("SORT_BLOCK " + std::to_string(ctx.params().i("sort_block")));
        prog_ = &ctx.program({"fullscreen.vert", "resolve_exact.frag"}, defines);
    }

    void execute(pathlet::PassContext& ctx) override {
        const GLuint nodes = ctx.buffer_texture("nodes", pathlet::oit::kNodeFormat);  // fill_list may have grown it
        const GLuint stats = ctx.buffer("stats").id;
        const GLuint zero[4] = {0, 0, 0, 0};
        // The last frame's draws wrote stats (atomics) and state (image stores): their writes
        // land before these updates only behind the update barriers.
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
        glNamedBufferSubData(stats, 0, sizeof(zero), zero);
        const GLuint fresh = 0;
        glClearTexImage(ctx.texture("state").id, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &fresh);
        const bool skip_empty = ctx.connected("coverage");
        if (skip_empty) {  // background everywhere first; the shader then runs on covered pixels only
            const glm::vec4 bg(ctx.params().v3("background"), 0.0f);
            glClearTexImage(ctx.texture("color").id, 0, GL_RGBA, GL_FLOAT, &bg.x);
        }
        ctx.bind_framebuffer({"color"}, skip_empty ? "coverage" : "");
        prog_->bind_texture("u_nodes", nodes);
        prog_->use();  // heads, carry, last, state, stats and the parameters by declaration
        prog_->set("u_visit_budget", int(kVisitBudget));
        // Draws until no pixel is pending: the cut and pending counts are read back after each
        // draw (a wait; the reference is asked for its pixels). Most frames finish in the first.
        const int max_draws = ctx.params().i("max_draws");
        int draws = 0;
        GLuint cut_pending[2] = {0, 1};  // stats words 2 and 3: pixels cut (this frame), pixels pending
        for (; cut_pending[1]; ++draws) {
            if (draws == max_draws)
                throw std::runtime_error(std::to_string(cut_pending[1]) + " pixels still pending after max_draws = " +
                                         std::to_string(max_draws) + " draws of " + std::to_string(kVisitBudget) +
                                         " node visits each; raise max_draws");
            glNamedBufferSubData(stats, 3 * sizeof(GLuint), sizeof(GLuint), &zero[0]);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
            if (skip_empty) {
                pathlet::lines::ScopedScissor clip(pathlet::lines::screen_rect(ctx, 2));
                ctx.draw_fullscreen_on_geometry(*prog_);
            } else {
                ctx.draw_fullscreen();
            }
            glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
            glGetNamedBufferSubData(stats, 2 * sizeof(GLuint), sizeof cut_pending, cut_pending);
        }
        ctx.stat("draws", double(draws));
        // This frame's own count, never an older or newer frame's: a cut pixel holds only part
        // of its fragments, so the frame is not exact (render's "incomplete frames" line).
        ctx.stat("truncated_pixels", double(cut_pending[0]));
        if (cut_pending[0]) ctx.frame_incomplete(ctx.frame_index());
        // The peaks through a fenced copy, read a frame or two late on a GPU (only statistics).
        if (!stats_) stats_ = std::make_unique<pathlet::GpuReadback>(sizeof peaks_seen_);
        if (const void* p = stats_->poll_newest()) std::memcpy(peaks_seen_, p, sizeof peaks_seen_);
        stats_->copy(stats, 0);
        ctx.stat("peak_nodes_per_pixel", double(peaks_seen_[0]));
        ctx.stat("peak_sort_rounds", double(peaks_seen_[1]));
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    std::unique_ptr<pathlet::GpuReadback> stats_;
    GLuint peaks_seen_[2] = {0, 0};  // the newest peaks known: list length, sorting rounds
    // Node visits per pixel and draw: far below the loop lengths drivers cut (llvmpipe cut
    // pixels of 125 rounds x 253 fragments), so only a single list this long is ever cut.
    static constexpr unsigned kVisitBudget = 8192;
};

pathlet::PassTypeInfo resolve_exact_type() {
    pathlet::PassTypeBuilder b("resolve_exact",
                               "the exact list resolve: every fragment of each pixel's list, sorted by depth in rounds "
                               "of a bounded block and composited front to back (the fragments at one depth as one "
                               "layer) until the transmittance left is below min_transmittance; no fragment cap");
    return pathlet::oit::declare_sort_block(b, "; a longer list takes more rounds, never fewer fragments")
        .param_float("min_transmittance", 1e-4, 0.0, 1.0,
                     "stop compositing a pixel when the light left through its fragments is below this (0: every "
                     "fragment)")
        .param_int("max_draws", 256, 1, 65536,
                   "draws of the resolve in a frame (each gives a pixel 8192 node visits, then carries its state to "
                   "the next); a frame that needs more fails, naming this")
        .param_color("background", {1.0f, 1.0f, 1.0f}, "colour behind all fragments")
        .input_texture("heads", "r32ui", "per-pixel list heads (fill_list)")
        .input_buffer("nodes", "list nodes (fill_list; with never_drop it holds every fragment)")
        .input_texture("coverage", "depth24",
                       "fill_list's coverage depth: when connected, pixels without fragments are only cleared",
                       {.optional = true})
        .internal_buffer("stats",
                         "peak list length, peak sorting rounds, pixels cut (a corrupt list, or a driver's loop "
                         "limit) and pixels pending for the next draw (uints)",
                         {.bytes = 16})
        .internal_texture("carry", "rgba32f", "a pending pixel's colour so far and transmittance left")
        .internal_texture("layer", "rgba32f", "a pending pixel's open layer: its fragments at one depth summed "
                                              "(shaders/oit_depth_group.glsl)")
        .internal_texture("last", "rgba32ui", "a pending pixel's last fragment taken: depth bits, line id, "
                                              "colour, node index")
        .internal_texture("state", "r32ui", "per pixel: fresh, pending or done (this frame)")
        .output_texture("color", "rgba8", "composited colour, alpha 1 where any fragment landed")
        .waits_for_gpu("an exact reference: after each draw it reads how many pixels are still pending, to draw "
                       "again until none is")
        .make<ResolveExact>();
}

}  // namespace

PATHLET_PLUGIN("resolve_exact", { sink->add(resolve_exact_type()); })
