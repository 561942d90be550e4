// bench_trace: tracer throughput (RK4 particle steps per second, 1 thread and all),
// study-phantom generation time and marching-cubes time. Prints numbers only.
#include "phantom/phantom.hpp"
#include "trace/marching_cubes.hpp"
#include "trace/tracer.hpp"

#include <chrono>
#include <ctime>
#include <cstdio>
#include <thread>

using namespace pathlet;

namespace {

// Wall seconds; also the process CPU seconds, which stay meaningful on a shared machine.
double cpu_seconds = 0.0;
template <class Fn>
double seconds(const Fn& fn) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    fn();
    cpu_seconds = double(std::clock() - c0) / CLOCKS_PER_SEC;
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main() {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    // Throughput without filtering, so every seed is integrated in full.
    auto o = phantom::phantom_preset("study");
    const trace::VelocityField field = phantom::make_phantom_field(o);
    trace::TraceOptions t = o.trace;
    t.min_distance = 0.0f;
    t.min_length = 0.0f;
    t.max_lines = 2000;
    for (int threads : {1, int(cores)}) {
        t.threads = threads;
        trace::TraceStats st;
        const double s = seconds([&] { trace::trace_pathlines(field, t, {}, &st); });
        std::printf("tracer  threads=%-2d  %9llu steps  %6.2f s wall (%.2f s cpu)  %.2f M steps/s wall, %.2f M per cpu-s (%zu seeds)\n",
                    threads, (unsigned long long)st.particle_steps, s, cpu_seconds, double(st.particle_steps) / s * 1e-6,
                    double(st.particle_steps) / cpu_seconds * 1e-6, st.candidates);
    }
    Mesh wall;
    const double mc = seconds([&] { wall = trace::marching_cubes(field.grid, field.mask, 0.5f); });
    std::printf("marching cubes  %dx%dx%d grid  %zu triangles  %.3f s\n", field.grid.dims.x, field.grid.dims.y,
                field.grid.dims.z, wall.index.size() / 3, mc);
    trace::TraceStats st;
    Scene scene;
    const double gen = seconds([&] { scene = phantom::make_phantom(o, {}, &st); });
    std::printf("phantom study  %zu lines  %zu points  %.2f s wall (%.2f s cpu) on %u threads\n", scene.lines.line_count(),
                scene.lines.point_count(), gen, cpu_seconds, cores);
    return 0;
}
