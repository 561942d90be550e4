#include "gpu_waits/gpu_waits.hpp"

#include <pathlet/gpu_fence.hpp>
#include <pathlet/pass.hpp>

#include <atomic>
#include <cstdlib>

namespace pathlet {

namespace {

std::atomic<int> g_override{-1};

// The pass being counted on this thread and whether this is its first frame.
struct Current {
    GpuWaitCount* count = nullptr;
    bool first_frame = false;
};
thread_local Current t_current;

}  // namespace

bool gpu_wait_counting() {
    const int o = g_override.load(std::memory_order_relaxed);
    if (o >= 0) return o != 0;
    static const bool debug = std::getenv("PATHLET_GL_DEBUG") != nullptr;
    return debug || simulated_gpu_latency() > 0;
}

void set_gpu_wait_counting(int on) { g_override.store(on < 0 ? -1 : (on ? 1 : 0), std::memory_order_relaxed); }

bool gpu_wait_allowed(const PassTypeInfo& type, const Params& params) {
    if (type.gpu_wait_reason.empty()) return false;
    return type.gpu_wait_when.empty() || params.b(type.gpu_wait_when);
}

void GpuWaitCounter::reset(size_t passes) {
    counts_.assign(passes, GpuWaitCount{});
    first_frame_.assign(passes, true);
}

void GpuWaitCounter::set_up(size_t pass) {
    if (pass < first_frame_.size()) first_frame_[pass] = true;
}

GpuWaitCounter::Scope::Scope(GpuWaitCounter& counter, size_t pass, uint64_t frame) : frame_(frame) {
    if (!gpu_wait_counting() || pass >= counter.counts_.size()) return;
    count_ = &counter.counts_[pass];
    later_before_ = count_->later;
    t_current = {count_, counter.first_frame_[pass]};
    counter.first_frame_[pass] = false;
}

GpuWaitCounter::Scope::~Scope() {
    if (!count_) return;
    t_current = {};
    if (count_->later == later_before_) return;
    if (count_->frames++ == 0) count_->first_waiting_frame = frame_;
}

std::string gpu_wait_line(const std::string& pass, const PassTypeInfo& type, const Params& params,
                          const GpuWaitCount& c) {
    if (c.later == 0) return "";
    std::string calls;
    for (const auto& [name, n] : c.calls) calls += (calls.empty() ? "" : ", ") + name + " " + std::to_string(n);
    const std::string what = "pass '" + pass + "' (" + type.type + ") waited for the GPU " + std::to_string(c.later) +
                             " times in " + std::to_string(c.frames) + " frames after its first (" + calls + ")";
    if (gpu_wait_allowed(type, params))
        return what + ", as its type declares: " + type.gpu_wait_reason;
    return "GPU WAIT: " + what + ", from frame " + std::to_string(c.first_waiting_frame) +
           ". A pass must not wait for the GPU in the frame loop: read results a frame or more late "
           "(pathlet/gpu_readback.hpp), or declare the wait (PassTypeBuilder::waits_for_gpu) if the pass is a "
           "reference that must";
}

namespace gpu_waits_detail {

void note(const char* call) {
    Current& c = t_current;
    if (!c.count) return;
    if (c.first_frame) {
        ++c.count->first_frame;
        return;
    }
    ++c.count->later;
    ++c.count->calls[call];
}

bool counting_here() { return t_current.count != nullptr; }

}  // namespace gpu_waits_detail

}  // namespace pathlet
