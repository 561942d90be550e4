#include "bench/calibration.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace pathlet::cli::bench {
namespace {

constexpr int kSize = 256, kDraws = 4;
// v2: a frame is many short passes, each waited for: on a loaded machine each wait also pays
// the scheduler's latency (hogs on every core took a frame from 5.5 to 12.5 ms while v1's one
// long draw said only 39 % slower). So the workload waits as often: kSyncs small draws (64x64),
// each followed by glFinish, before the long one.
constexpr int kSyncs = 8, kSmall = 64;
// Changing these changes what every recorded calibration means: never edit them, add another.
constexpr const char* kVert = R"(#version 450 core
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
})";
constexpr const char* kFrag = R"(#version 450 core
layout(location = 0) out vec4 o;
void main() {
    vec2 x = gl_FragCoord.xy * 0.013;
    for (int i = 0; i < 48; ++i) x = vec2(sin(x.y * 1.7 + 0.3), cos(x.x * 1.3 - 0.2)) + 0.01 * x;
    o = vec4(x * 0.5 + 0.5, 0.0, 1.0);
})";

GLuint compile(GLenum stage, const char* src) {
    const GLuint s = glCreateShader(stage);
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = {0};
        glGetShaderInfoLog(s, sizeof log - 1, nullptr, log);
        glDeleteShader(s);
        throw std::runtime_error(std::string("bench calibration: shader does not compile: ") + log);
    }
    return s;
}

}  // namespace

Calibration::Calibration() {
    const GLuint v = compile(GL_VERTEX_SHADER, kVert), f = compile(GL_FRAGMENT_SHADER, kFrag);
    prog_ = glCreateProgram();
    glAttachShader(prog_, v);
    glAttachShader(prog_, f);
    glLinkProgram(prog_);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(prog_, GL_LINK_STATUS, &ok);
    if (!ok) throw std::runtime_error("bench calibration: the program does not link");
    glCreateVertexArrays(1, &vao_);
    glCreateTextures(GL_TEXTURE_2D, 1, &tex_);
    glTextureStorage2D(tex_, 1, GL_RGBA8, kSize, kSize);
    glCreateFramebuffers(1, &fbo_);
    glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, tex_, 0);
    sample_ms();  // compiles the shader's variant on first use (llvmpipe's JIT): not a sample
}

Calibration::~Calibration() {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &tex_);
    glDeleteVertexArrays(1, &vao_);
    glDeleteProgram(prog_);
}

double Calibration::sample_ms() {
    GLint old_fbo = 0, old_vp[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &old_fbo);
    glGetIntegerv(GL_VIEWPORT, old_vp);
    glFinish();
    const auto t0 = std::chrono::steady_clock::now();
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, kSize, kSize);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(prog_);
    glBindVertexArray(vao_);
    glViewport(0, 0, kSmall, kSmall);
    for (int i = 0; i < kSyncs; ++i) {
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glFinish();
    }
    glViewport(0, 0, kSize, kSize);
    for (int i = 0; i < kDraws; ++i) glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(old_fbo));
    glViewport(old_vp[0], old_vp[1], old_vp[2], old_vp[3]);
    return ms;
}

std::vector<double> Calibration::samples_ms(int n) {
    std::vector<double> v;
    for (int i = 0; i < n; ++i) v.push_back(sample_ms());
    return v;
}

const char* Calibration::description() {
    return "GL: 8 draws of a 48-step sin/cos fragment loop into 64x64, each waited for, then 4 into 256x256 RGBA8, "
           "glFinish-bracketed (v2)";
}

double median_of(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace pathlet::cli::bench
