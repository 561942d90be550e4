// Scaling table: how the cost of a frame grows with lines and with pixels. The study phantom is
// repeated 1x, 4x and 16x (every copy after the first shifted by a small random offset, so the
// copies do not draw onto the same pixels), and each graph is rendered at each size. Per cell:
// median frame, the three largest passes' shares, the scene's GPU memory (vertex buffer), the
// process's resident memory and its growth over the measured frames (must stay 0: no per-frame
// allocation), and the load time (repeat + upload, including the level-of-detail build).
//   build/bin/bench_scaling [--graphs variant1_lineao,isl] [--scales 1,4,16]
//                           [--sizes 1280x720,1920x1080,3840x2160] [--frames 3] [--window 1]
#include "frame_capture.hpp"
#include "phantom/phantom.hpp"
#include "renderer.hpp"

#include <pathlet/gpu_scene.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

using namespace pathlet;

namespace {

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    for (std::string t; std::getline(in, t, ',');)
        if (!t.empty()) out.push_back(t);
    return out;
}

double rss_mib() {
    std::ifstream f("/proc/self/statm");
    size_t pages = 0, resident = 0;
    f >> pages >> resident;
    return double(resident) * 4096.0 / 1048576.0;
}

// k copies of the lines; copy c > 0 shifted by up to `jitter` world units per axis.
Scene repeat(const Scene& base, int k, float jitter) {
    Scene s;
    s.mesh = base.mesh;
    s.source = base.source + " x" + std::to_string(k);
    const Pathlines& b = base.lines;
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> u(-jitter, jitter);
    for (int c = 0; c < k; ++c) {
        const glm::vec3 shift = c == 0 ? glm::vec3(0) : glm::vec3(u(rng), u(rng), u(rng));
        const uint32_t offset = uint32_t(s.lines.position.size());
        for (const glm::vec3& p : b.position) s.lines.position.push_back(p + shift);
        s.lines.time.insert(s.lines.time.end(), b.time.begin(), b.time.end());
        s.lines.velocity.insert(s.lines.velocity.end(), b.velocity.begin(), b.velocity.end());
        for (LineRange r : b.lines) s.lines.lines.push_back({r.first + offset, r.count});
    }
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> graphs{"variant1_lineao", "isl"};
    std::vector<int> scales{1, 4, 16};
    std::vector<std::string> sizes{"1280x720", "1920x1080", "3840x2160"};
    int frames = 3;
    double window = 1.0;
    for (int i = 1; i + 1 < argc; i += 2) {
        std::string k = argv[i], v = argv[i + 1];
        if (k == "--graphs") graphs = split(v);
        else if (k == "--scales") {
            scales.clear();
            for (const auto& s : split(v)) scales.push_back(std::max(1, std::atoi(s.c_str())));
        } else if (k == "--sizes") sizes = split(v);
        else if (k == "--frames") frames = std::max(1, std::atoi(v.c_str()));
        else if (k == "--window") window = std::atof(v.c_str());
        else {
            std::fprintf(stderr, "bench_scaling: unknown option %s (see the comment at the top of bench_scaling.cpp)\n", k.c_str());
            return 2;
        }
    }
    Scene base = phantom::load_or_make_phantom("study");
    const float jitter = 0.002f * glm::length(base.bounds().hi - base.bounds().lo);
    Runtime& rt = test_runtime();
    std::printf("scaling: study phantom (%zu lines, %zu points) repeated, window %.2f s, t = 9 s, %d frames, %s\n",
                base.lines.line_count(), base.lines.position.size(), window, frames,
                rt.ensure_gl(true).renderer().c_str());
    std::printf("%-6s %-10s %-16s %9s %9s %9s  %-44s %8s %8s %8s %7s\n", "lines", "size", "graph", "median", "p5",
                "p95", "largest passes (share of the frame)", "scene", "rss", "growth", "load");
    std::printf("%-6s %-10s %-16s %9s %9s %9s  %-44s %8s %8s %8s %7s\n", "", "", "", "(ms)", "(ms)", "(ms)", "",
                "(MiB)", "(MiB)", "(MiB)", "(s)");
    for (int k : scales) {
        auto t0 = std::chrono::steady_clock::now();
        Scene scene = repeat(base, k, jitter);
        double upload_s = 0;
        {
            // The upload (vertex buffer, level-of-detail build) as every render does it.
            auto u0 = std::chrono::steady_clock::now();
            GpuScene gpu;
            gpu.upload(scene);
            glFinish();
            upload_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - u0).count();
        }
        const double load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double scene_mib = double(scene.lines.position.size()) * 48.0 / 1048576.0;
        for (const auto& size : sizes)
            for (const auto& g : graphs) {
                RenderOptions opt;
                opt.graph_path = resolve_graph_path(g);
                opt.size = parse_size(size);
                opt.time.start = opt.time.end = 9.0;
                opt.repeat = frames;
                opt.warmup = 1;
                opt.write_images = false;
                opt.quiet = true;
                opt.sets = {"window=" + std::to_string(window)};
                double rss_first = 0, rss_last = 0;
                RenderResult res = render(rt, scene, opt, [&](const Executor&, size_t i) {
                    (i == 0 ? rss_first : rss_last) = rss_mib();
                });
                if (frames == 1) rss_last = rss_first;
                const auto f = res.profiler.frame_ms();
                auto passes = res.profiler.passes();
                std::sort(passes.begin(), passes.end(),
                          [](const auto& a, const auto& b) { return a.gpu_ms.median > b.gpu_ms.median; });
                std::string top;
                for (size_t i = 0; i < passes.size() && i < 3; ++i) {
                    char buf[64];
                    std::snprintf(buf, sizeof buf, "%s%s %.0f%%", i ? ", " : "", passes[i].name.c_str(),
                                  100.0 * passes[i].gpu_ms.median / std::max(f.median, 1e-9));
                    top += buf;
                }
                std::printf("%-6s %-10s %-16s %9.1f %9.1f %9.1f  %-44s %8.0f %8.0f %8.1f %7.2f\n",
                            (std::to_string(k) + "x").c_str(), size.c_str(), g.c_str(), f.median, f.p5, f.p95,
                            top.c_str(), scene_mib, rss_last, rss_last - rss_first, load_s);
                std::fflush(stdout);
            }
        std::printf("  (%dx: %zu lines, %zu points; repeat + upload %.2f s, of it upload and level of detail %.2f s)\n",
                    k, scene.lines.line_count(), scene.lines.position.size(), load_s, upload_s);
    }
    return 0;
}
