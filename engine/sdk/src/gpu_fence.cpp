#include <pathlet/gpu_fence.hpp>

#include <atomic>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace pathlet {

namespace {

std::atomic<uint64_t> g_frame{0};
std::atomic<int> g_override{-1};

int latency_from_env() {
    const char* v = std::getenv("PATHLET_SIMULATE_GPU_LATENCY");
    if (!v || !*v) return 0;
    char* end = nullptr;
    const long k = std::strtol(v, &end, 10);
    if (*end != '\0' || k < 0 || k > 1000)
        throw std::runtime_error(std::string("PATHLET_SIMULATE_GPU_LATENCY='") + v +
                                 "': expected a whole number of frames 1..1000 (0 or unset: off)");
    return int(k);
}

}  // namespace

uint64_t gpu_frame() { return g_frame.load(std::memory_order_relaxed); }
void advance_gpu_frame() { g_frame.fetch_add(1, std::memory_order_relaxed); }

int simulated_gpu_latency() {
    const int o = g_override.load(std::memory_order_relaxed);
    if (o >= 0) return o;
    static const int k = latency_from_env();
    return k;
}

void set_simulated_gpu_latency(int frames) { g_override.store(frames < 0 ? -1 : frames, std::memory_order_relaxed); }

bool simulated_latency_passed(uint64_t issued_frame) {
    const int k = simulated_gpu_latency();
    if (k <= 0) return true;
    const uint64_t now = gpu_frame(), kk = uint64_t(k);
    return now >= issued_frame + kk && now % kk == 0;
}

GpuFence GpuFence::insert() {
    GpuFence f;
    f.sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    f.frame_ = gpu_frame();
    return f;
}

GpuFence& GpuFence::operator=(GpuFence&& o) noexcept {
    if (this != &o) {
        reset();
        sync_ = o.sync_;
        frame_ = o.frame_;
        o.sync_ = nullptr;
    }
    return *this;
}

void GpuFence::reset() {
    if (sync_) glDeleteSync(sync_);
    sync_ = nullptr;
}

bool GpuFence::signalled(bool flush) const {
    if (!sync_) return true;
    if (!simulated_latency_passed(frame_)) return false;  // a later check flushes it
    const GLenum r = glClientWaitSync(sync_, flush ? GL_SYNC_FLUSH_COMMANDS_BIT : 0, 0);
    return r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED;
}

void GpuFence::wait() const {
    if (!sync_) return;
    for (;;) {  // one second at a time; a lost context returns GL_WAIT_FAILED
        const GLenum r = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000);
        if (r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED) return;
        if (r == GL_WAIT_FAILED) throw std::runtime_error("waiting for the GPU failed (glClientWaitSync: GL_WAIT_FAILED)");
    }
}

bool query_ready(GLuint query, uint64_t issued_frame) {
    if (!simulated_latency_passed(issued_frame)) return false;
    GLint available = 0;
    glGetQueryObjectiv(query, GL_QUERY_RESULT_AVAILABLE, &available);
    return available != 0;
}

}  // namespace pathlet
