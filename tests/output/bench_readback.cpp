// Render-thread time per frame of reading outputs back (prints numbers; not a test):
// lineao_debug's six captures (rgba8 colour and final, rgba16f normal+depth, r32f zoom, r16f AO,
// depth24) at a size given on the command line (default 1920x1080), each frame read
//   before: as the output side did at 42c2715: every non-8-bit target as RGBA32F, depth through
//           GL_DEPTH_COMPONENT, into a pack buffer, then mapped, zero-filled and copied into a
//           vector on the render thread (ReadbackRing::take) once the fence signalled;
//   after:  AsyncOutput::capture() + poll(): own formats, depth as R32F where exact, the mapped
//           buffer handed to a writer (the writer's widening is not on the render thread).
// Both glFinish-bracketed (llvmpipe runs the copies on the calling thread: its timer queries
// do not measure); the fastest frame and the median (the fastest is the one least disturbed by
// other work on the machine). Usage: bench_readback [WxH] [frames]
#include "frame_capture.hpp"
#include "executor.hpp"
#include "frames/async_output.hpp"
#include "formats.hpp"
#include "renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>

using namespace pathlet;
using Clock = std::chrono::steady_clock;

namespace {

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

// The 42c2715 path for one texture, up to the bytes in a vector on the render thread.
size_t legacy_read(const Texture& t) {
    const FormatInfo* fi = find_format(t.internal_format);
    const bool depth = fi && fi->depth, bytes8 = fi && fi->pixel_type == GL_UNSIGNED_BYTE && !fi->depth;
    const GLenum format = depth ? GL_DEPTH_COMPONENT : GL_RGBA, type = bytes8 ? GL_UNSIGNED_BYTE : GL_FLOAT;
    const size_t bpp = depth || bytes8 ? 4 : 16, bytes = size_t(t.width) * size_t(t.height) * bpp;
    GLuint pbo = 0;
    glCreateBuffers(1, &pbo);
    glNamedBufferStorage(pbo, GLsizeiptr(bytes), nullptr, GL_MAP_READ_BIT | GL_CLIENT_STORAGE_BIT);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, pbo);
    glGetTextureImage(t.id, 0, format, type, GLsizei(bytes), nullptr);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 10'000'000'000ull);
    glDeleteSync(fence);
    std::vector<float> data;
    if (const void* p = glMapNamedBufferRange(pbo, 0, GLsizeiptr(bytes), GL_MAP_READ_BIT)) {
        data.resize((bytes + 3) / 4);
        std::memcpy(data.data(), p, bytes);
        glUnmapNamedBuffer(pbo);
    }
    glDeleteBuffers(1, &pbo);
    return bytes;
}

}  // namespace

int main(int argc, char** argv) {
    int w = 1920, h = 1080, frames = 6;
    if (argc > 1 && std::sscanf(argv[1], "%dx%d", &w, &h) != 2) {
        std::fprintf(stderr, "usage: bench_readback [WxH] [frames]\n");
        return 2;
    }
    if (argc > 2) frames = std::max(2, std::atoi(argv[2]));
    const std::vector<std::string> outputs = {"color", "normal_depth", "zoom", "depth", "ao", "final"};
    RenderOptions o;
    o.graph_path = std::string(PATHLET_SOURCE_DIR) + "/graphs/lineao_debug.json";
    o.size = {w, h};
    o.time = {4.0, 4.0 + 0.1 * (frames - 1), 0.1};
    o.write_images = false;  // the render reads nothing itself: both paths are timed here
    o.quiet = true;
    o.warmup = 1;
    std::vector<double> before, after;
    size_t before_bytes = 0;
    uint64_t after_bytes = 0;
    std::unique_ptr<AsyncOutput> out;
    render(test_runtime(), small_phantom_scene(), o, [&](const Executor& e, size_t) {
        std::vector<AsyncOutput::Capture> caps;
        for (const auto& name : outputs) caps.push_back({"output '" + name + "'", e.texture(name), "", false});
        if (!out) {  // formats measured (byte tables, the filter, the depth copy) outside the timing
            out = std::make_unique<AsyncOutput>(AsyncOutput::Options{});
            out->capture(caps);
            out->finish();
        }
        glFinish();
        auto t0 = Clock::now();
        before_bytes = 0;
        for (const auto& c : caps) before_bytes += legacy_read(c.tex);
        glFinish();
        before.push_back(ms_since(t0));
        const uint64_t b0 = out->bytes_read_back();
        t0 = Clock::now();
        out->capture(caps);
        out->poll();
        glFinish();
        after.push_back(ms_since(t0));
        after_bytes = out->bytes_read_back() - b0;
    });
    out->finish();
    std::printf("lineao_debug, %dx%d, %zu frames, %s\n", w, h, before.size(), test_runtime().gl->renderer().c_str());
    auto least = [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); };
    std::printf("  before (RGBA32F, depth component, copy on the render thread): %7.1f ms fastest, %7.1f median, %6.1f MiB read\n",
                least(before), median(before), double(before_bytes) / 1048576.0);
    std::printf("  after  (own formats, mapped buffers to the writers):            %7.1f ms fastest, %7.1f median, %6.1f MiB read\n",
                least(after), median(after), double(after_bytes) / 1048576.0);
    return 0;
}
