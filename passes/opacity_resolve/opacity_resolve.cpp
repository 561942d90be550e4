// opacity_resolve: opacity optimization, step 2. A compute shader over opacity_lists' lists
// (as many work groups as the lists ask for in their header: glDispatchComputeIndirect, so the
// resolution is said once, by opacity_lists) sorts every pixel's fragments and gives each
// segment the least opacity of the decoupled closed form over its fragments (Günther, Theisel,
// Gross 2017), for opacity_blend. The parameters q, r and lambda are the energy's.
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <string>
#include <vector>

namespace {

// The targets' header (shaders/opacity_optimization.glsl): count, blend work groups (x, 1, 1),
// peak, beyond, truncated, 0.
constexpr GLuint kTargetHeader[8] = {0, 0, 1, 1, 0, 0, 0, 0};
constexpr GLuint kUnseen = 0xFFFFFFFFu;  // OO_UNSEEN

class OpacityResolve : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        // The pins' storage bindings come from the engine (LISTS_BINDING, SEGMENTS_BINDING, ...).
        prog_ = &ctx.program({"opacity_resolve.comp"}, {"MAX_FRAGMENTS " + std::to_string(ctx.params().i("max_fragments"))});
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
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
        prog_->use();  // q, r, lambda and the pins by declaration
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, lists.id);
        glDispatchComputeIndirect(0);  // the lists' work groups (their header's first words)
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
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
        .param_int("max_fragments", 32, 1, 64,
                   "nearest fragments per pixel that get an opacity (all of them count as occluders); a longer list "
                   "is counted in the targets' header")
        .input_buffer("lists", "opacity_lists' per-pixel lists")
        .input_buffer("segments", "opacity_lists' segmentation")
        .output_buffer("targets",
                       "per segment the least opacity its fragments asked for (OO_UNSEEN: none), the segments that "
                       "got one, and the work groups opacity_blend needs (shaders/opacity_optimization.glsl)",
                       {.bytes = 32})
        .make<OpacityResolve>();
}

}  // namespace

PATHLET_PLUGIN("opacity_resolve", { sink->add(opacity_resolve_type()); })
