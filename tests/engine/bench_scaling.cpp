// Scaling table: how the cost of a frame grows with lines and with pixels. The study phantom is
// made 1x, 4x and 16x denser ("study:density=N": N times the lines, more seeds in the same
// vessel and time span), and each graph is rendered at each size. Per cell: median frame, the
// three largest passes' shares, the line points' GPU memory (GpuScene::point_memory), the
// process's resident memory and its growth over the measured frames (must stay 0: no per-frame
// allocation), and the load time (the cached phantom read + upload, including the level of
// detail and the chunks; a phantom not cached yet is generated first, timed apart).
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
    Runtime& rt = test_runtime();
    std::printf("scaling: study phantom made denser, window %.2f s, t = 9 s, %d frames, %s, %s points\n", window, frames,
                rt.ensure_gl(true).renderer().c_str(), GpuScene::layout_name(GpuScene::default_point_layout()));
    std::printf("%-6s %-10s %-16s %9s %9s %9s  %-44s %8s %8s %8s %7s\n", "lines", "size", "graph", "median", "p5",
                "p95", "largest passes (share of the frame)", "scene", "rss", "growth", "load");
    std::printf("%-6s %-10s %-16s %9s %9s %9s  %-44s %8s %8s %8s %7s\n", "", "", "", "(ms)", "(ms)", "(ms)", "",
                "(MiB)", "(MiB)", "(MiB)", "(s)");
    for (int k : scales) {
        const std::string spec = "study" + (k > 1 ? ":density=" + std::to_string(k) : std::string());
        const auto g0 = std::chrono::steady_clock::now();
        phantom::load_or_make_phantom(spec);  // generated and cached on first use, timed apart
        const double made_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - g0).count();
        const auto t0 = std::chrono::steady_clock::now();
        const Scene scene = phantom::load_or_make_phantom(spec);
        double upload_s = 0, scene_mib = 0, per_point = 0;
        {
            // The upload (point buffers, level of detail, chunks) as every render does it.
            auto u0 = std::chrono::steady_clock::now();
            GpuScene gpu;
            gpu.upload(scene);
            glFinish();
            upload_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - u0).count();
            scene_mib = double(gpu.point_memory().total()) / 1048576.0;
            per_point = gpu.point_memory().per_point();
        }
        const double load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
        std::printf("  (%dx: %zu lines, %zu points, %.1f B a point on the GPU; load + upload %.2f s, of it upload, level "
                    "of detail and chunks %.2f s; first call %.1f s)\n",
                    k, scene.lines.line_count(), scene.lines.position.size(), per_point, load_s, upload_s, made_s);
    }
    return 0;
}
