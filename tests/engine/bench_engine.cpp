// Engine benchmarks (print numbers; not tests):
//  1. compile time of a 50-pass graph (parse + validate + compile + pooling);
//  2. per-frame engine overhead: a pattern + blur graph run by the Executor (with and without
//     the profiler) against the same GL calls issued by hand, at 1280x720 (GPU work dominates)
//     and as a 50-pass chain at 8x8 (almost pure bookkeeping).
#include "engine_test_util.hpp"

#include "gl_context.hpp"
#include "graph/hook_params.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

using namespace pathlet;
using namespace pathlet::testing_util;
using Clock = std::chrono::steady_clock;

namespace {

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

std::string chain_graph(int n) {
    json g = {{"version", 1}, {"name", "chain" + std::to_string(n)}, {"passes", json::array()}, {"resources", json::object()}};
    g["passes"].push_back({{"name", "p0"}, {"type", "fullscreen"}, {"outputs", {{"color", "r0"}}}});
    g["resources"]["r0"] = json::object();
    for (int i = 1; i < n; ++i) {
        std::string in = "r" + std::to_string(i - 1), out = "r" + std::to_string(i);
        g["passes"].push_back({{"name", "p" + std::to_string(i)},
                               {"type", "blur"},
                               {"params", {{"radius", 1}}},
                               {"inputs", {{"src", in}}},
                               {"outputs", {{"dst", out}}}});
        g["resources"][out] = json::object();
    }
    g["outputs"] = json::array({{{"resource", "r" + std::to_string(n - 1)}}});
    return g.dump(1);
}

void bench_compile(Runtime& rt) {
    std::string text = chain_graph(50);
    std::vector<double> t;
    size_t before = 0, after = 0;
    for (int i = 0; i < 30; ++i) {
        auto t0 = Clock::now();
        GraphFile g = parse_graph_json(text, "chain50.json");
        CompiledGraph cg = compile_graph(g, rt.registry, {1920, 1080});
        t.push_back(ms_since(t0));
        before = cg.memory_unpooled, after = cg.memory_pooled;
    }
    std::printf("compile, 50-pass graph (parse+validate+compile+pool), median of 30: %.3f ms\n", median(t));
    std::printf("  memory at 1920x1080: %.1f MiB before pooling, %.1f MiB after\n", before / 1048576.0, after / 1048576.0);
}

// The same GL work as the chain graph (pattern, then n-1 separable blurs) issued by hand.
struct ByHand {
    ShaderProgram pattern, blur;
    std::vector<GLuint> tex, fbo;
    GLuint vao = 0;
    glm::ivec2 size;
    ByHand(const Executor& e, Runtime& rt, int n, glm::ivec2 sz) : size(sz) {
        pattern = ShaderProgram::from_files({"fullscreen.vert", "gradient.frag"}, shader_search_path(*rt.registry.find("fullscreen"), {}));
        blur = ShaderProgram::from_files({"fullscreen.vert", "blur.frag"}, shader_search_path(*rt.registry.find("blur"), {}));
        tex.resize(size_t(2 * n));
        fbo.resize(tex.size());
        glCreateTextures(GL_TEXTURE_2D, GLsizei(tex.size()), tex.data());
        glCreateFramebuffers(GLsizei(fbo.size()), fbo.data());
        for (size_t i = 0; i < tex.size(); ++i) {
            glTextureStorage2D(tex[i], 1, i % 2 ? GL_RGBA16F : GL_RGBA8, size.x, size.y);
            glNamedFramebufferTexture(fbo[i], GL_COLOR_ATTACHMENT0, tex[i], 0);
        }
        glCreateVertexArrays(1, &vao);
    }
    ~ByHand() {
        glDeleteTextures(GLsizei(tex.size()), tex.data());
        glDeleteFramebuffers(GLsizei(fbo.size()), fbo.data());
        glDeleteVertexArrays(1, &vao);
    }
    void frame() {
        glBindVertexArray(vao);
        glViewport(0, 0, size.x, size.y);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo[0]);
        pattern.use();
        pattern.set("u_param", glm::vec3(1, 1, 1));
        pattern.set("u_strength", 1.0f);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        blur.use();
        for (size_t i = 2; i < tex.size(); i += 2) {
            blur.set("u_radius", 1);
            blur.set("u_sigma", 2.0f);
            glBindFramebuffer(GL_FRAMEBUFFER, fbo[i - 1]);  // horizontal into the rgba16f temp
            glBindTextureUnit(0, tex[i - 2]);
            blur.set("u_dir", glm::vec2(1, 0));
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindFramebuffer(GL_FRAMEBUFFER, fbo[i]);
            glBindTextureUnit(0, tex[i - 1]);
            blur.set("u_dir", glm::vec2(0, 1));
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
};

// Frames of the three variants interleaved (so machine load drifts hit all alike), each
// closed by glFinish; prints medians and the executor's overhead against the hand version.
void bench_overhead(Runtime& rt, int n, glm::ivec2 size, int frames) {
    Scene scene = tiny_scene();
    GpuScene gpu;
    gpu.upload(scene);
    CompiledGraph cg = compile_graph(parse_graph_json(chain_graph(n), "chain.json"), rt.registry, size);
    Executor plain(*rt.gl, cg, gpu, nullptr);
    plain.setup();
    Profiler prof;
    prof.init(TimingBackend::GlTimestamp, rt.gl->renderer());  // timestamps: no extra glFinish
    Executor profiled(*rt.gl, cg, gpu, &prof);
    profiled.setup();
    ByHand hand(plain, rt, n, size);
    std::vector<double> t_hand, t_exec, t_prof;
    for (int i = 0; i < frames + 3; ++i) {
        auto run = [&](std::vector<double>& out, auto&& f) {
            glFinish();
            auto t0 = Clock::now();
            f();
            glFinish();
            if (i >= 3) out.push_back(ms_since(t0));
        };
        run(t_hand, [&] { hand.frame(); });
        run(t_exec, [&] { plain.run_frame({uint64_t(i), 0.0, Camera{}}); });
        run(t_prof, [&] { profiled.run_frame({uint64_t(i), 0.0, Camera{}}); });
    }
    prof.release_gl();
    double h = median(t_hand), e = median(t_exec), p = median(t_prof);
    std::printf("%d-pass chain (pattern + %d blurs) at %dx%d, median of %d interleaved frames:\n", n, n - 1, size.x,
                size.y, frames);
    std::printf("  by hand            %9.3f ms\n", h);
    std::printf("  executor           %9.3f ms  (%+.1f%%)\n", e, 100.0 * (e - h) / h);
    std::printf("  executor+profiler  %9.3f ms  (%+.1f%%, GL timestamps)\n", p, 100.0 * (p - h) / h);
}

}  // namespace

int main() {
    Runtime& rt = runtime();
    std::printf("%s\n", rt.gl->summary().c_str());
    bench_compile(rt);
    bench_overhead(rt, 2, {1280, 720}, 40);   // a realistic frame: the GPU work dominates
    bench_overhead(rt, 50, {8, 8}, 100);      // almost pure bookkeeping: the engine's own cost
    return 0;
}
