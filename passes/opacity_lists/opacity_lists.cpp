// opacity_lists: opacity optimization's first pass (Günther et al. 2013; the decoupled form of
// Günther, Theisel, Gross 2017). The pathlets of the time window, drawn through the line kit at
// a reduced resolution, become per-pixel lists of (segment, depth, importance) for
// opacity_resolve. A segment is a piece of a line of about segment_length line widths, keyed to
// the line and its arc length (shaders/opacity_optimization.glsl), so the opacity found for it
// stays with the pathline as the window moves.
//
// Importance: the segment's mean speed or mean of a point array, on a fixed range (the data's
// 1st to 99th percentile unless importance_min/max say), to the power importance_exponent; times
// the opacity of the pass's colour hook where it has one (fade_opacity.frag: a faded end matters
// less; a fragment faded out is no node). Or, with importance=hook, the colour hook's opacity
// alone, every fragment kept as an occluder: importance as a GLSL function of LinePoint.
//
// Nothing is read back in the frame: the node counter of every frame is copied aside with a
// fence (pathlet::GpuReadback) and read, every count in order, when the GPU is done (the next
// frame on llvmpipe, a few later in bursts on a GPU). As fill_list, the lists grow ahead when a
// frame used more than kGrowAt of them, to kHeadroom x that count; a frame that still overflowed
// lost fragments: it is reported (stats, stderr, PassContext::frame_incomplete) and the lists
// grow for the frames after it. finish() waits for the counts in flight at the end of a run.
#include "segmentation.hpp"

#include <pathlet/gl_limits.hpp>
#include <pathlet/gpu_readback.hpp>
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace lines = pathlet::lines;
namespace oo = opacity_lists;

// The lists' layout (shaders/opacity_optimization.glsl): header words, node words.
constexpr size_t kListHeaderWords = 8, kNodeWords = 4;
constexpr uint32_t kEnd = 0xFFFFFFFFu;   // OO_END
constexpr uint32_t kCountWord = 6;       // OO_LIST_COUNT
constexpr uint32_t kResolveGroup = 8;    // opacity_resolve's work group is 8 x 8

// Every segmentation gets its own generation, so opacity_blend never blends a segment with the
// state of another segmentation's segment of the same index.
std::atomic<uint32_t> g_generation{1};

enum class Importance { speed, array, hook };

bool iequals(const std::string& a, const std::string& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
           });
}

// importance=array's per-point field: any array `pathlet info` lists. The importers keep the
// file's other arrays in Pathlines::arrays (a vector as its magnitude); the arrays they read as
// the pathlines' velocity and time (by the names they look for) are the lines' own: velocity as
// its magnitude (the speed), time as it is.
std::vector<float> importance_field(const pathlet::Pathlines& pl, const std::string& name) {
    const pathlet::PointArray* a = pl.array(name);
    for (size_t i = 0; !a && i < pl.arrays.size(); ++i)
        if (iequals(pl.arrays[i].name, name)) a = &pl.arrays[i];
    if (a) return a->values;
    const bool has_velocity = pl.velocity.size() == pl.position.size() && !pl.timeless;
    const bool has_time = pl.time.size() == pl.position.size() && !pl.timeless;
    std::vector<float> field;
    if (has_velocity)
        for (const char* v : {"velocity", "vel", "u", "v", "speed"})
            if (iequals(name, v)) {
                field.resize(pl.position.size());
                for (size_t i = 0; i < field.size(); ++i) field[i] = glm::length(pl.velocity[i]);
                return field;
            }
    if (has_time)
        for (const char* t : {"time", "t", "integrationtime"})
            if (iequals(name, t)) return pl.time;
    std::string names;
    if (has_velocity) names = "velocity (as its magnitude)";
    if (has_time) names += std::string(names.empty() ? "" : ", ") + "time";
    for (const auto& x : pl.arrays) names += (names.empty() ? "" : ", ") + x.name;
    throw std::runtime_error("importance_array '" + name + "': the data has no point array of that name; its arrays: " +
                             (names.empty() ? std::string("none") : names));
}

size_t list_words(glm::ivec2 size, size_t nodes) {
    const size_t heads = (kListHeaderWords + size_t(size.x) * size_t(size.y) + 3) & ~size_t(3);
    return heads + kNodeWords * nodes;
}

class OpacityLists : public pathlet::Pass {
public:
    ~OpacityLists() override {
        if (fbo_) glDeleteFramebuffers(1, &fbo_);
    }

    void setup(pathlet::PassContext& ctx) override {
        const pathlet::Params& p = ctx.params();
        const auto importance = p.e<Importance>("importance");
        // The pins' bindings come from the engine (LISTS_BINDING, ...).
        const std::vector<std::string> defines =
            importance == Importance::hook ? std::vector<std::string>{"OO_IMPORTANCE_HOOK"} : std::vector<std::string>{};
        prog_ = &lines::program(ctx, {"opacity_lists.frag"}, lines::hooks(ctx), defines);
        drawer_.set_depth_func(GL_ALWAYS);  // every fragment, as OIT keeps them

        // The segments and their importance: static for the data set and these parameters.
        const pathlet::Pathlines& pl = ctx.scene().cpu().lines;
        const std::vector<float> arc = oo::arc_lengths(pl);
        const float length = p.f("segment_length") * lines::line_width(ctx);
        const oo::Segmentation seg = oo::segment_lines(pl, arc, length);
        std::vector<float> g(seg.segments(), 1.0f);
        if (importance != Importance::hook) {
            std::vector<float> field(pl.position.size());
            float lo = p.f("importance_min"), hi = p.f("importance_max");
            const bool automatic = !(hi > lo);
            if (importance == Importance::speed) {
                for (size_t i = 0; i < field.size(); ++i) field[i] = glm::length(pl.velocity[i]);
                if (automatic) lo = ctx.scene().speed_min(), hi = ctx.scene().speed_max();
            } else {
                field = importance_field(pl, p.s("importance_array"));
                if (automatic) lo = oo::quantile(field, 0.01), hi = oo::quantile(field, 0.99);
            }
            if (!(hi > lo)) hi = lo + 1.0f;  // a constant field: everything as important
            g = oo::segment_means(pl, arc, seg, field);
            const float exponent = p.f("importance_exponent");
            for (float& x : g) x = std::isfinite(x) ? std::pow(std::clamp((x - lo) / (hi - lo), 0.0f, 1.0f), exponent) : 0.0f;
            range_ = {lo, hi};
        }
        const uint32_t generation = g_generation.fetch_add(1);
        const std::vector<uint32_t> with_importance = oo::pack(seg, generation, &g);
        segments_bytes_ = 4 * (with_importance.size() - seg.segments());  // the public part
        pathlet::check_storage_block(4 * with_importance.size(), "opacity_lists' segments and importance",
                                     "for " + std::to_string(seg.segments()) + " segments", "raise segment_length");
        const pathlet::Buffer source = ctx.grow_buffer("source", 4 * with_importance.size());
        glNamedBufferSubData(source.id, 0, GLsizeiptr(4 * with_importance.size()), with_importance.data());
        ctx.grow_buffer("segments", segments_bytes_);
        segments_ = seg.segments();

        const GLint64 max_block = pathlet::gl_limits().get(GL_MAX_SHADER_STORAGE_BLOCK_SIZE);
        const size_t cap = size_t(p.f("max_memory_mb") * 1048576.0);
        max_bytes_ = std::max<size_t>(64, std::min(size_t(std::max<GLint64>(max_block, 0)), cap));
        if (!counts_) counts_ = std::make_unique<pathlet::GpuReadback>(sizeof(GLuint));
        if (!fbo_) glCreateFramebuffers(1, &fbo_);
    }

    void execute(pathlet::PassContext& ctx) override {
        const pathlet::Params& p = ctx.params();
        const glm::ivec2 out = ctx.output_size();
        const float res = p.f("resolution");
        const glm::ivec2 size = glm::max(glm::ivec2(glm::ceil(glm::vec2(out) * res)), glm::ivec2(1));
        const size_t pixels = size_t(size.x) * size_t(size.y);
        const size_t max_nodes = max_bytes_ / 4 > list_words(size, 0) ? (max_bytes_ / 4 - list_words(size, 0)) / kNodeWords : 0;
        if (max_nodes == 0)
            throw std::runtime_error("max_memory_mb (or GL_MAX_SHADER_STORAGE_BLOCK_SIZE) leaves no room for nodes at " +
                                     std::to_string(size.x) + "x" + std::to_string(size.y));
        max_nodes_ = max_nodes;
        // Every earlier frame's count the GPU is done with (never waited for), in order, tagged with
        // that frame's capacity: grow ahead for this frame, and report the frames that overflowed.
        double dropped = -1;
        GLuint peak = 0;
        counts_->poll([&](const pathlet::GpuReadback::Result& r) {
            const GLuint count = *static_cast<const GLuint*>(r.data);
            peak = std::max(peak, count);
            dropped = take_count(ctx, r, max_nodes);  // the newest frame's, for the stat
        });
        if (double(peak) > kGrowAt * double(capacity_)) wanted_ = std::max(wanted_, size_t(kHeadroom * double(peak)) + 1);
        const size_t by_pixels = size_t(std::ceil(p.f("nodes_per_pixel") * double(pixels)));
        capacity_ = std::min(max_nodes, std::max({by_pixels, wanted_, size_t(1)}));
        const pathlet::Buffer lists = ctx.grow_buffer("lists", 4 * list_words(size, capacity_));
        capacity_ = std::min(max_nodes, (lists.bytes / 4 - list_words(size, 0)) / kNodeWords);

        const GLuint header[kListHeaderWords] = {GLuint((size.x + kResolveGroup - 1) / kResolveGroup),
                                                 GLuint((size.y + kResolveGroup - 1) / kResolveGroup),
                                                 1,
                                                 GLuint(size.x),
                                                 GLuint(size.y),
                                                 GLuint(std::min<size_t>(capacity_, 0xFFFFFFFEu)),
                                                 0,
                                                 0};
        glNamedBufferSubData(lists.id, 0, sizeof header, header);
        glClearNamedBufferSubData(lists.id, GL_R32UI, GLintptr(sizeof header), GLsizeiptr(4 * pixels), GL_RED_INTEGER,
                                  GL_UNSIGNED_INT, &kEnd);
        // The public segments, every frame (the resource may be pooled with others between frames).
        glCopyNamedBufferSubData(ctx.buffer("source").id, ctx.buffer("segments").id, 0, 0, GLsizeiptr(segments_bytes_));

        glNamedFramebufferParameteri(fbo_, GL_FRAMEBUFFER_DEFAULT_WIDTH, size.x);
        glNamedFramebufferParameteri(fbo_, GL_FRAMEBUFFER_DEFAULT_HEIGHT, size.y);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        glViewport(0, 0, size.x, size.y);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        prog_->use();  // lists and source on their bindings by declaration
        drawer_.draw(ctx, *prog_);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        counts_->copy(lists.id, 4 * kCountWord, capacity_, ctx.frame_index());

        ctx.stat("segments_total", double(segments_));
        ctx.stat("list_width", size.x);
        ctx.stat("list_height", size.y);
        ctx.stat("capacity_nodes", double(capacity_));
        ctx.stat("node_memory_mib", double(lists.bytes) / 1048576.0);
        ctx.stat("overflow_events_total", double(events_));
        if (dropped >= 0) ctx.stat("dropped_fragments_last_frame", dropped);  // of the counts that arrived
        ctx.stat("count_waits", double(counts_->waits()));  // copies that found the ring full (GpuReadback)
        ctx.stat("importance_min", range_.x);
        ctx.stat("importance_max", range_.y);
    }

    // The end of the run: the counts still in flight, waited for, so every lost frame is reported.
    void finish(pathlet::PassContext& ctx) override {
        if (counts_) counts_->drain([&](const pathlet::GpuReadback::Result& r) { take_count(ctx, r, max_nodes_); });
    }

private:
    static constexpr double kGrowAt = 0.75, kHeadroom = 1.5;  // fill_list's grow-ahead

    // One frame's count, tagged with its capacity: the fragments it lost (0 when it fit).
    double take_count(pathlet::PassContext& ctx, const pathlet::GpuReadback::Result& r, size_t max_nodes) {
        const GLuint count = *static_cast<const GLuint*>(r.data);
        const size_t had = size_t(r.tag);
        if (count <= had) return 0.0;
        ++events_;
        ctx.frame_incomplete(r.frame);
        if (had < max_nodes) {
            wanted_ = std::max(wanted_, size_t(double(count) * kHeadroom) + 1);
            std::fprintf(stderr, "%s: node buffer overflow in frame %llu: %u fragments for %zu nodes, %zu lost; growing to %zu nodes\n",
                         ctx.pass_name().c_str(), (unsigned long long)r.frame, count, had, size_t(count - had),
                         std::min(wanted_, max_nodes));
        } else {
            std::fprintf(stderr, "%s: frame %llu DROPS %zu of %u fragments: the lists are at their cap (max_memory_mb = %g)\n",
                         ctx.pass_name().c_str(), (unsigned long long)r.frame, size_t(count - had), count,
                         double(ctx.params().f("max_memory_mb")));
        }
        return double(count - had);
    }

    pathlet::ShaderProgram* prog_ = nullptr;
    lines::Drawer drawer_;
    GLuint fbo_ = 0;
    std::unique_ptr<pathlet::GpuReadback> counts_;  // the lists' node counts, a frame or more late
    size_t segments_bytes_ = 0, segments_ = 0, capacity_ = 0, wanted_ = 0, max_bytes_ = 0;
    size_t max_nodes_ = 0;  // the last frame's (finish() has no frame)
    long long events_ = 0;
    glm::vec2 range_{0.0f, 1.0f};
};

pathlet::PassTypeInfo opacity_lists_type() {
    pathlet::PassTypeBuilder b("opacity_lists",
                               "opacity optimization, step 1: the window's pathlets at a reduced resolution into "
                               "per-pixel lists of (segment, depth, importance); segments are pieces of a line keyed to "
                               "its arc length, importance the segment's speed, a point array, or a colour hook");
    lines::declare_params(b)
        .param_float("resolution", 0.5, 0.05, 1.0,
                     "size of the lists relative to the output (0.5: a quarter of the pixels; the reference "
                     "implementations' default)")
        .param_float("segment_length", 4.0, 0.25, 1000.0,
                     "length of an opacity segment in line widths (the kit's width: scale-free); every line gets "
                     "its length / this, rounded, at least one")
        .param_enum("importance", "speed", {"speed", "array", "hook"},
                    "what makes a segment important: speed (its mean speed) or array (its mean of the point array "
                    "importance_array), times the colour hook's opacity where there is one (fade_opacity.frag: the "
                    "end fade); or hook: the colour hook's opacity alone (its alpha is the importance)")
        .param_string("importance_array", "", "the point array of the data for importance=array (pathlet info lists them)")
        .param_float("importance_min", 0.0, -1e30, 1e30,
                     "value of importance 0 (speed or array); importance_max <= importance_min: the data's 1st "
                     "percentile (speed: the colour map's automatic range)")
        .param_float("importance_max", 0.0, -1e30, 1e30, "value of importance 1; see importance_min")
        .param_float("importance_exponent", 1.0, 0.1, 10.0,
                     "importance = (value on the range)^this: above 1 fewer segments are important, so the many slow ones "
                     "clear each other less (dense flow tends to be faded alike, Tuncay & Guenther 2024)")
        .param_float("nodes_per_pixel", 8.0, 0.01, 1024.0,
                     "initial node capacity per list pixel (16 bytes a node); grown after a frame that overflowed")
        .param_float("max_memory_mb", 512.0, 0.01, 65536.0,
                     "cap for the lists in MiB (also GL_MAX_SHADER_STORAGE_BLOCK_SIZE); beyond it fragments are "
                     "dropped and counted")
        .output_buffer("lists",
                       "per-pixel lists at the reduced resolution: header, heads, nodes (segment, depth, importance, "
                       "next); layout shaders/opacity_optimization.glsl",
                       {.bytes = 4 * kListHeaderWords})
        .output_buffer("segments",
                       "the segmentation: header, per line its first segment, count and segment length, per segment "
                       "its line (shaders/opacity_optimization.glsl)",
                       {.bytes = 16})
        .internal_buffer("source", "the segmentation with each segment's importance, made at setup",
                         {.bytes = 16}, {.persistent = true});
    return b.make<OpacityLists>();
}

}  // namespace

PATHLET_PLUGIN("opacity_lists", { sink->add(opacity_lists_type()); })
