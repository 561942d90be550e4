// fill_list: variant 2's second pass (seed §III.c). Rasterises the pathlets of the time window
// through the line kit into per-pixel linked lists, with opacity ramping from 0 at the tail to
// full and back to 0 at the head (the kit's end fade). Colour writes are masked as in the seed:
// nothing goes to a framebuffer, only to the lists. Or, with its G-buffer outputs bound, the
// same raster also writes variant 2's opaque G-buffer for LineAO (what a separate gbuffer pass
// would draw: one raster of the window instead of two, the same lists).
//
// Overflow is never silent. The first frame after the graph is built reads the node counter back
// after the draw (a wait, once): on overflow the buffer grows (x1.25 the count, within
// max_memory_mb and the GL buffer-texture limit) and the frame's lists are rebuilt, so a single
// picture is whole. Later frames never wait (issue 34: a GPU idles while the CPU waits, and its
// clock drops), nor does a parameter change (setup() again): every frame's counter is copied
// through a fenced ring (pathlet::GpuReadback) and read when the GPU is done, every count in
// order; the buffer grows ahead when a frame used more than kGrowAt of it, to kHeadroom x that
// count. A frame that still overflowed lost fragments: it is logged, counted (stats) and
// reported as incomplete (PassContext::frame_incomplete) when its count arrives, or at the end of
// the run (finish() waits for the counts in flight), and the buffer grows for the next. With
// never_drop (exact references) every frame is handled as the first: it waits for its count, is
// redrawn after growing, and fails at the cap instead of dropping.
#include <pathlet/lines.hpp>
#include <pathlet/gpu_readback.hpp>
#include <pathlet/oit.hpp>
#include <pathlet/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace lines = pathlet::lines;
namespace oit = pathlet::oit;

class FillList : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        // counts_ stays: only the first frame after the graph is built waits for its count (a
        // parameter change must not drain the GPU; what overflows after it is found late).
        records_ = ctx.connected("records");
        coverage_ = ctx.connected("coverage");
        gbuffer_ = lines::gbuffer_targets(ctx);
        writes_gbuffer_ = ctx.connected("depth");
        if (writes_gbuffer_ && coverage_)
            throw std::runtime_error("bind 'coverage' or the G-buffer's 'depth', not both (with the G-buffer, its "
                                     "depth is the coverage)");
        if (!writes_gbuffer_ && !gbuffer_.pins.empty())
            throw std::runtime_error("the G-buffer outputs (" + gbuffer_.pins.front() + ", ...) need 'depth' bound too");
        std::vector<std::string> defines = oit::defines();
        if (writes_gbuffer_) {
            defines.push_back("WRITE_GBUFFER");
            defines.insert(defines.end(), gbuffer_.defines.begin(), gbuffer_.defines.end());
        }
        if (records_) {
            defines.push_back("WRITE_RECORDS");
            for (const auto& d : lines::density_defines(ctx)) defines.push_back(d);
        }
        prog_ = &lines::program(ctx, {"fill_list.frag"}, lines::hooks(ctx), defines);
        GLint max_texels = 0;
        glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
        const size_t cap_bytes = size_t(ctx.params().f("max_memory_mb") * 1024.0 * 1024.0);
        max_nodes_ = std::max<size_t>(1, std::min(size_t(max_texels), cap_bytes / oit::kNodeBytes));
        if (writes_gbuffer_) {
            // The G-buffer's depth test keeps its nearest fragment, after the shader ran (it
            // writes gl_FragDepth): every fragment still reaches its list, and no chunk may be
            // occlusion-culled, since what the G-buffer hides is still a node.
            drawer_.set_depth_func(GL_LEQUAL);
            drawer_.set_occlusion_culling(false);
            return;
        }
        // Without the G-buffer: a raster with no colour attachments, only the optional coverage
        // depth (every fragment kept: depth test ALWAYS).
        drawer_.set_depth_func(GL_ALWAYS);
    }

    void execute(pathlet::PassContext& ctx) override {
        const glm::ivec2 size = ctx.output_size();
        const size_t pixels = size_t(size.x) * size_t(size.y);
        const size_t wanted = std::min(max_nodes_, size_t(std::ceil(ctx.params().f("nodes_per_pixel") * double(pixels))));
        size_t capacity = ensure_capacity(ctx, std::max<size_t>(wanted, 1));
        if (!counts_ || ctx.params().b("never_drop")) {
            first_frame(ctx, capacity);
            if (!counts_) counts_ = std::make_unique<pathlet::GpuReadback>(sizeof(GLuint));
            return;
        }
        // Every count that arrived, in frame order, each tagged with the capacity its frame had.
        Late late;
        counts_->poll([&](const pathlet::GpuReadback::Result& r) { take_count(ctx, r, late); });
        if (double(late.peak) > kGrowAt * double(capacity) && capacity < max_nodes_) {
            const size_t before = capacity;
            capacity = ensure_capacity(ctx, std::min(max_nodes_, size_t(kHeadroom * double(late.peak)) + 1));
            if (late.dropped && capacity > before)
                std::fprintf(stderr, "%s: node buffer grown to %zu nodes (%.1f MiB)\n", ctx.pass_name().c_str(), capacity,
                             double(capacity * oit::kNodeBytes) / 1048576.0);
        }
        draw(ctx, capacity);
        counts_->copy(ctx.buffer("counter").id, 0, capacity, ctx.frame_index());
        ctx.stat("count_waits", double(counts_->waits()));  // copies that found the ring full (GpuReadback)
        report(ctx, last_count_, capacity, late.events, late.dropped);
    }

    // The end of the run: the counts still in flight, waited for, so every lost frame is reported.
    void finish(pathlet::PassContext& ctx) override {
        Late late;
        if (counts_) counts_->drain([&](const pathlet::GpuReadback::Result& r) { take_count(ctx, r, late); });
    }

private:
    struct Late {  // what the counts that arrived in one call said
        GLuint peak = 0;
        int events = 0;
        size_t dropped = 0;
    };

    // One frame's count, a frame or more late: a frame with more fragments than nodes lost some.
    void take_count(pathlet::PassContext& ctx, const pathlet::GpuReadback::Result& r, Late& late) {
        const GLuint count = *static_cast<const GLuint*>(r.data);
        const size_t had = size_t(r.tag);
        last_count_ = count;
        late.peak = std::max(late.peak, count);
        if (count <= had) return;
        const size_t dropped = count - had;
        late.dropped += dropped;
        ++late.events;
        ++events_total_;
        ctx.frame_incomplete(r.frame);
        if (had >= max_nodes_)
            report_cap(ctx, r.frame, dropped, count, had);
        else
            std::fprintf(stderr, "%s: node buffer overflow in frame %llu: %u fragments for %zu nodes, %zu lost\n",
                         ctx.pass_name().c_str(), (unsigned long long)r.frame, count, had, dropped);
    }

    // Grows the node buffer to hold `nodes` (never shrinks) and points the buffer texture at it.
    size_t ensure_capacity(pathlet::PassContext& ctx, size_t nodes) {
        pathlet::Buffer b = ctx.grow_buffer("nodes", nodes * oit::kNodeBytes);
        if (records_) ctx.grow_buffer("records", b.bytes);  // the same indices
        return std::min(max_nodes_, b.bytes / oit::kNodeBytes);
    }

    // The first frame: waits for its count, and on overflow grows and draws the frame again.
    void first_frame(pathlet::PassContext& ctx, size_t capacity) {
        GLuint count = draw_and_count(ctx, capacity);
        int events = 0;
        if (count > capacity && capacity < max_nodes_) {
            ++events;
            ++events_total_;
            const size_t grown = ensure_capacity(ctx, std::min(max_nodes_, size_t(double(count) * 1.25) + 1));
            std::fprintf(stderr,
                         "%s: node buffer overflow in frame %llu: %u fragments for %zu nodes; grown to %zu nodes "
                         "(%.1f MiB) and the frame re-rendered\n",
                         ctx.pass_name().c_str(), (unsigned long long)ctx.frame_index(), count, capacity, grown,
                         double(grown * oit::kNodeBytes) / 1048576.0);
            capacity = grown;
            oit::clear_lists(ctx.texture("heads").id, ctx.buffer("counter").id);
            count = draw_and_count(ctx, capacity);
        }
        const size_t dropped = count > capacity ? count - capacity : 0;
        if (dropped && ctx.params().b("never_drop")) {  // a reference frame is whole or not made
            char msg[320];
            std::snprintf(msg, sizeof msg,
                          "never_drop: the frame needs %u nodes (%.1f MiB), more than the cap of %zu nodes "
                          "(max_memory_mb = %g, or GL_MAX_TEXTURE_BUFFER_SIZE); raise max_memory_mb, shorten the "
                          "window or render smaller",
                          count, double(count) * double(oit::kNodeBytes) / 1048576.0, capacity,
                          double(ctx.params().f("max_memory_mb")));
            throw std::runtime_error(msg);
        }
        if (dropped) {
            report_cap(ctx, ctx.frame_index(), dropped, count, capacity);
            ctx.frame_incomplete(ctx.frame_index());
        }
        last_count_ = count;
        report(ctx, count, capacity, events, dropped);
    }

    GLuint draw_and_count(pathlet::PassContext& ctx, size_t capacity) {
        draw(ctx, capacity);
        GLuint count = 0;
        glGetNamedBufferSubData(ctx.buffer("counter").id, 0, sizeof(count), &count);  // waits for the draw
        return count;
    }

    void report_cap(pathlet::PassContext& ctx, uint64_t frame, size_t dropped, GLuint count, size_t capacity) const {
        std::fprintf(stderr,
                     "%s: frame %llu DROPS %zu of %u fragments: the node buffer is at its cap (%zu nodes, "
                     "max_memory_mb = %g); raise max_memory_mb or shorten the window\n",
                     ctx.pass_name().c_str(), (unsigned long long)frame, dropped, count, capacity,
                     ctx.params().f("max_memory_mb"));
    }

    void report(pathlet::PassContext& ctx, GLuint count, size_t capacity, int events, size_t dropped) const {
        ctx.stat("nodes", double(count));
        ctx.stat("capacity_nodes", double(capacity));
        ctx.stat("node_memory_mib", double(capacity * oit::kNodeBytes) / 1048576.0);
        ctx.stat("overflow_events", double(events));
        ctx.stat("overflow_events_total", double(events_total_));
        ctx.stat("dropped_fragments", double(dropped));
    }

    // Appends the window's fragments to the lists (the counter may pass the capacity: those
    // fragments are not stored).
    void draw(pathlet::PassContext& ctx, size_t capacity) {
        if (writes_gbuffer_) {
            lines::bind_gbuffer(ctx, gbuffer_, *prog_);  // cleared again when an overflow re-renders
        } else {
            ctx.bind_framebuffer({}, coverage_ ? "coverage" : "");
            if (coverage_) {
                glDepthMask(GL_TRUE);
                const float far = 1.0f;
                glClearBufferfv(GL_DEPTH, 0, &far);
            }
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);  // the seed: colour writes masked
        }
        // heads (image) and counter (storage block) are bound by declaration; the buffers as images:
        prog_->bind_image("u_nodes", ctx.buffer_texture("nodes", oit::kNodeFormat), oit::kNodeFormat, GL_WRITE_ONLY);
        if (records_)
            prog_->bind_image("u_records", ctx.buffer_texture("records", oit::kNodeFormat), oit::kNodeFormat, GL_WRITE_ONLY);
        prog_->use();
        prog_->set("u_capacity", int(std::min<size_t>(capacity, 0x7fffffff)));
        drawer_.draw(ctx, *prog_);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        // Texture update: the heads' next glClearTexImage (and a glGetTextureImage) follow the atomics.
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                        GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    }

    static constexpr double kGrowAt = 0.75, kHeadroom = 1.5;

    pathlet::ShaderProgram* prog_ = nullptr;
    lines::Drawer drawer_;
    bool coverage_ = false, records_ = false, writes_gbuffer_ = false;
    lines::GBufferTargets gbuffer_;  // the bound G-buffer colour targets (only with 'depth')
    size_t max_nodes_ = 1;
    long long events_total_ = 0;
    std::unique_ptr<pathlet::GpuReadback> counts_;  // later frames' counts, without waiting
    GLuint last_count_ = 0;                         // the newest count known
};

pathlet::PassTypeInfo fill_list_type() {
    pathlet::PassTypeBuilder b("fill_list",
                               "variant 2: pathlet fragments into per-pixel linked lists (OIT) with the opacity of "
                               "their colour hook (by default the kit's end fade); the node buffer grows on overflow; "
                               "with `depth` bound also the opaque G-buffer of the same fragments, for LineAO");
    lines::declare_params(b, {.color = "fade_opacity.frag"})
        .param_float("nodes_per_pixel", 4.0, 0.01, 1024.0,
                     "initial node capacity per output pixel (16 bytes a node); grown automatically on overflow")
        .param_float("max_memory_mb", 1024.0, 0.01, 65536.0,
                     "cap for the node buffer in MiB (also capped by GL_MAX_TEXTURE_BUFFER_SIZE nodes); a frame "
                     "that needs more drops fragments and says so (with never_drop: fails, naming it)")
        .param_bool("never_drop", false,
                    "every frame waits for its node count and, on overflow, grows the buffer and draws again; a frame "
                    "over max_memory_mb fails instead of dropping (exact references: a wait per frame)")
        .waits_for_gpu("never_drop (exact references): every frame reads its node count to grow the buffer and "
                       "draw again before it drops a fragment",
                       "never_drop")
        .input_texture("heads", "r32ui", "per-pixel list heads, cleared by clear_list")
        .input_buffer("counter", "node counter, cleared by clear_list")
        .output_texture("coverage", "depth24",
                        "depth < 1 where any fragment landed (bind it so resolve_list skips empty tiles); not with "
                        "the G-buffer outputs, whose depth serves the same",
                        {.optional = true})
        .output_buffer("nodes",
                       "the nodes (uvec4: colour, depth, next, line id), grown to nodes_per_pixel x pixels and on "
                       "overflow",
                       {.bytes = oit::kNodeBytes})
        .output_buffer("records",
                       "per node, what the line kit's volume AO needs (line_volume_ao_pack: normal, tangent, axis, "
                       "opacity), grown with the nodes: resolve_list shades every fragment by its own AO (bind it "
                       "to get it)",
                       {.bytes = oit::kNodeBytes}, {.optional = true});
    // Bound (with `depth`): the opaque G-buffer of the same fragments, for LineAO, in this raster.
    lines::declare_gbuffer_outputs(b, /*optional=*/true);
    return b.make<FillList>();
}

}  // namespace

PATHLET_PLUGIN("fill_list", { sink->add(fill_list_type()); })
