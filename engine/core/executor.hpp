// Runs a compiled graph: owns the physical GL objects (one per pool slot, two per history
// resource), instantiates the passes, calls setup() once and execute() every frame, each
// inside a profiler scope, with GL errors and exceptions turned into messages that name
// the pass.
#pragma once

#include "frames/frames_in_flight.hpp"
#include "gpu_waits/gpu_waits.hpp"
#include "graph/graph_model.hpp"
#include "pass_context.hpp"

#include <pathlet/gpu_scene.hpp>
#include <pathlet/pass.hpp>
#include <pathlet/shader.hpp>

#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlet {

class AsyncOutput;

class GlContext;
class Profiler;

class Executor final : private PassHost {
public:
    // `cg`, `scene` and `gl` must outlive the executor. `profiler` may be null.
    Executor(GlContext& gl, const CompiledGraph& cg, const GpuScene& scene, Profiler* profiler = nullptr);
    ~Executor();
    Executor(const Executor&) = delete;
    Executor& operator=(const Executor&) = delete;

    void setup();                         // resources, pass instances, Pass::setup()
    // Every pass in order, then history swap; first waits until fewer than PATHLET_FRAMES_IN_FLIGHT
    // frames are in flight on the GPU (frames/frames_in_flight.hpp).
    void run_frame(const FrameInfo& f);
    // The end of a run: every pass's finish() (late counts waited for and reported).
    void finish();
    // Frames a pass reported as incomplete (PassContext::frame_incomplete), by FrameInfo::index.
    const std::set<uint64_t>& incomplete_frames() const { return incomplete_; }
    // Each pass's waits for the GPU in its execute() (counted under PATHLET_GL_DEBUG and the
    // latency mode, gpu_waits/gpu_waits.hpp), by pass index.
    const std::vector<GpuWaitCount>& gpu_waits() const { return gpu_waits_.counts(); }
    // After the owner of the compiled graph changed passes[i].params: the pass sees the new
    // parameters and its setup() runs again (the Pass contract), without rebuilding anything
    // else. Throws PassError naming the pass; the pass then keeps its old parameters.
    void reparam(size_t i);

    const CompiledGraph& graph() const override { return cg_; }
    Texture texture(const std::string& resource) const;  // current content (after run_frame)
    Buffer buffer(const std::string& resource) const;
    // Where pass i's shaders come from (its search path and hook files): what the viewer watches.
    const ShaderSource& shaders(size_t i) const { return contexts_.at(i)->shaders; }

private:
    // PassHost: what the passes' contexts ask for.
    const GpuScene& scene() const override { return scene_; }
    const FrameInfo& frame() const override { return frame_; }
    Physical& physical(int resource, bool previous) override;
    GLuint framebuffer(const std::vector<GLuint>& color, GLuint depth, int mip, const std::string& pass) override;
    GLuint empty_vertex_array() const override { return empty_vao_; }
    void stat(const std::string& pass, const std::string& name, double value) override;
    void frame_incomplete(uint64_t frame) override { incomplete_.insert(frame); }
    AsyncOutput& pass_output() override;
    void used(const PassBindings& bindings, int uniform_blocks) override;

    Physical make_physical(const PoolSlot& s, const std::string& label);
    const Physical& current(int resource) const;
    void check_gl(const std::string& pass, const char* phase);
    void reset_gl_state();

    GlContext& gl_;
    const CompiledGraph& cg_;
    const GpuScene& scene_;
    Profiler* profiler_;
    std::vector<Physical> slots_;                 // by slot index
    std::map<int, Physical> history_prev_;        // resource -> last frame's object
    std::vector<std::unique_ptr<Pass>> passes_;
    std::vector<std::unique_ptr<PassContextImpl>> contexts_;
    std::map<std::vector<GLuint>, GLuint> fbos_;
    GLuint empty_vao_ = 0;
    // The most units and binding points any pass was given: what the reset between passes unbinds.
    int max_samplers_ = 0, max_images_ = 0, max_bindings_ = 0, max_blocks_ = 0;
    FrameInfo frame_;
    FramesInFlight frames_in_flight_;
    std::set<uint64_t> incomplete_;
    GpuWaitCounter gpu_waits_;
    std::unique_ptr<AsyncOutput> pass_output_;  // PassContext::write_image's files (the capture pass)
};

}  // namespace pathlet
