#include <pathlet/gpu_fence.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <thread>
#include <stdexcept>
#include <string>

namespace pathlet {

namespace {

std::atomic<uint64_t> g_frame{0};
std::atomic<int> g_override{-1};
std::atomic<double> g_wait_limit{0.0};  // > 0: a test's
std::atomic<bool> g_hung{false};

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

double wait_limit_from_env() {
    const char* v = std::getenv("PATHLET_GPU_WAIT_LIMIT");
    if (!v || !*v) return 120.0;
    char* end = nullptr;
    const double s = std::strtod(v, &end);
    if (*end != '\0' || !(s > 0.0) || !std::isfinite(s))
        throw std::runtime_error(std::string("PATHLET_GPU_WAIT_LIMIT='") + v +
                                 "': expected the seconds a wait for the GPU may take, a number > 0 (default 120)");
    return s;
}

}  // namespace

double gpu_wait_limit_seconds() {
    const double t = g_wait_limit.load(std::memory_order_relaxed);
    if (t > 0.0) return t;
    static const double env = wait_limit_from_env();
    return env;
}
void set_gpu_wait_limit(double seconds) { g_wait_limit.store(seconds > 0.0 ? seconds : 0.0, std::memory_order_relaxed); }
void set_simulated_gpu_hang(bool hung) { g_hung.store(hung, std::memory_order_relaxed); }

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
    if (g_hung.load(std::memory_order_relaxed)) return false;
    if (!simulated_latency_passed(frame_)) return false;  // a later check flushes it
    const GLenum r = glClientWaitSync(sync_, flush ? GL_SYNC_FLUSH_COMMANDS_BIT : 0, 0);
    return r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED;
}

void GpuFence::wait() const {
    if (!sync_) return;
    const double limit = gpu_wait_limit_seconds();
    const auto start = std::chrono::steady_clock::now();
    auto waited = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    // At most a second at a time (less near the limit); a lost context returns GL_WAIT_FAILED.
    for (;;) {
        const double left = limit - waited();
        if (left <= 0.0)
            throw std::runtime_error("the GPU did not finish the work of frame " + std::to_string(frame_) + " within " +
                                     std::to_string(int(std::ceil(limit))) +
                                     " s (a hung GPU or driver; PATHLET_GPU_WAIT_LIMIT sets the limit)");
        const GLuint64 ns = GLuint64(std::min(left, 1.0) * 1e9);
        if (g_hung.load(std::memory_order_relaxed)) {  // a test's GPU that never signals
            std::this_thread::sleep_for(std::chrono::nanoseconds(std::min<GLuint64>(ns, 10'000'000)));
            continue;
        }
        const GLenum r = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, ns);
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
