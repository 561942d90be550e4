// bench_io: load speed of every pathline format at study scale (3169 lines, 644,104
// points, time + velocity). Prints points/second and file size per format. Not a test.
// Usage: bench_io [DIR]   (default: a temp dir; files are removed afterwards)
#include "io/pathline_formats.hpp"
#include "io/pathline_io.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <unistd.h>

using namespace pathlet;
using namespace pathlet::io;
namespace fs = std::filesystem;

static Pathlines synthesize() {
    const size_t lines = 3169, points = 644104;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Pathlines p;
    p.position.reserve(points);
    for (size_t l = 0; l < lines; ++l) {
        size_t n = points / lines + (l < points % lines ? 1 : 0);
        uint32_t first = uint32_t(p.position.size());
        glm::vec3 x{u(rng) * 20, u(rng) * 20, u(rng) * 40};
        float t = 0.001f * float(l % 100);
        for (size_t k = 0; k < n; ++k) {
            glm::vec3 v{std::sin(0.05f * float(k) + float(l)), std::cos(0.07f * float(k)), 0.8f + 0.1f * u(rng)};
            p.position.push_back(x);
            p.time.push_back(t);
            p.velocity.push_back(v * 0.5f);
            x += v * 0.005f;
            t += 0.005f;
        }
        p.lines.push_back({first, uint32_t(n)});
    }
    return p;
}

int main(int argc, char** argv) {
    fs::path dir = argc > 1 ? fs::path(argv[1]) : fs::temp_directory_path() / ("pathlet-bench-io-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    Pathlines p = synthesize();
    std::printf("bench_io: %zu lines, %zu points (time + velocity)\n", p.line_count(), p.point_count());
    std::printf("%-22s %12s %10s %10s %14s\n", "format", "size (MB)", "write (s)", "load (s)", "Mpoints/s");
    struct F { const char* name; PathlineFormat fmt; const char* ext; };
    const F formats[] = {{"VtkAscii", PathlineFormat::VtkAscii, ".vtk"},          {"VtkBinary", PathlineFormat::VtkBinary, ".vtk"},
                         {"VtpAscii", PathlineFormat::VtpAscii, ".vtp"},          {"VtpBinary (base64)", PathlineFormat::VtpBinary, ".vtp"},
                         {"VtpAppendedRaw", PathlineFormat::VtpAppendedRaw, ".vtp"}, {"VtpAppendedBase64", PathlineFormat::VtpAppendedBase64, ".vtp"},
                         {"VtpZlib", PathlineFormat::VtpZlib, ".vtp"},            {"Native", PathlineFormat::Native, ".pathlet"}};
    using clk = std::chrono::steady_clock;
    auto secs = [](clk::time_point a, clk::time_point b) { return std::chrono::duration<double>(b - a).count(); };
    for (const F& f : formats) {
        std::string path = (dir / (std::string("bench_") + f.name[0] + std::to_string(int(f.fmt)) + f.ext)).string();
        auto t0 = clk::now();
        save_pathlines(p, path, f.fmt);
        auto t1 = clk::now();
        double best = 1e30;
        int reps = 3;
        size_t loaded = 0;
        for (int r = 0; r < reps; ++r) {  // best of 3: the first run warms the page cache
            auto a = clk::now();
            Pathlines q = load_pathlines(path);
            best = std::min(best, secs(a, clk::now()));
            loaded = q.point_count();
        }
        if (loaded != p.point_count()) std::printf("  !! %s loaded %zu points\n", f.name, loaded);
        std::printf("%-22s %12.2f %10.3f %10.4f %14.1f\n", f.name, double(fs::file_size(path)) / 1e6, secs(t0, t1), best,
                    double(loaded) / best / 1e6);
    }
    if (argc <= 1) fs::remove_all(dir);
    return 0;
}
