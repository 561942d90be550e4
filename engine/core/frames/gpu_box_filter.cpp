#include "frames/gpu_box_filter.hpp"

#include "frames/output_program.hpp"
#include "frames/raw_frame.hpp"
#include "image_io.hpp"
#include "pixel_store.hpp"

#include <cstring>
#include <random>
#include <stdexcept>
#include <string>

namespace pathlet {

namespace {

// box_downsample's loops: image rows top-down (GL rows from the block's top), columns left to
// right, colour weighted by alpha, alpha, the plain colour; `precise` keeps each multiply and
// add a rounded IEEE operation of its own, in this order.
constexpr const char* kBoxFilterFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D u_src;
uniform int u_factor;
layout(location = 0) out vec4 o_sums;
void main() {
    const ivec2 p = ivec2(gl_FragCoord.xy);
    const int f = u_factor;
    precise vec4 sum = vec4(0.0);
    precise vec3 plain = vec3(0.0);
    for (int j = 0; j < f; ++j)
        for (int i = 0; i < f; ++i) {
            const vec4 s = texelFetch(u_src, ivec2(p.x * f + i, p.y * f + (f - 1 - j)), 0);
            sum.rgb = sum.rgb + s.a * s.rgb;
            sum.a = sum.a + s.a;
            plain = plain + s.rgb;
        }
    o_sums = sum.a <= 0.0 ? vec4(plain, sum.a) : sum;
}
)";

}  // namespace

GpuBoxFilter::~GpuBoxFilter() {
    if (vao_) glDeleteVertexArrays(1, &vao_);
    if (program_) glDeleteProgram(program_);
}

void GpuBoxFilter::ensure_program() {
    if (program_) return;
    program_ = link_output_program(kBoxFilterFragment, "GPU box filter");
    factor_loc_ = glGetUniformLocation(program_, "u_factor");
    glCreateVertexArrays(1, &vao_);
}

GLuint GpuBoxFilter::sums(GLuint src, int w, int h, int factor, size_t slot) {
    ensure_program();
    const OutputTargets::Target& t = targets_.at(slot, w, h);
    glProgramUniform1i(program_, factor_loc_, factor);
    draw_output_program(program_, vao_, t.fbo, w, h, src);
    return t.tex;
}

bool GpuBoxFilter::exact(GLenum internal_format, int factor) {
    const auto key = std::make_pair(internal_format, factor);
    auto it = exact_.find(key);
    if (it == exact_.end()) it = exact_.emplace(key, measure(internal_format, factor)).first;
    return it->second;
}

bool GpuBoxFilter::measure(GLenum internal_format, int factor) {
    // Odd block counts catch a flipped or shifted block; blocks without alpha take the plain
    // mean; 8-bit steps with alpha 1 put many means exactly half-way between two 8-bit values.
    const int w = 13, h = 11, W = w * factor, H = h * factor;
    std::mt19937 rng(1234);
    std::uniform_int_distribution<int> byte(0, 255);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> pattern(size_t(W) * size_t(H) * 4);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            float* p = &pattern[(size_t(y) * size_t(W) + size_t(x)) * 4];
            const int block = (x / factor) + (y / factor) * w;
            for (int c = 0; c < 4; ++c) p[c] = block % 2 ? unit(rng) : float(byte(rng)) / 255.0f;
            if (block % 5 == 0) p[3] = 0.0f;
            else if (block % 3 == 0) p[3] = 1.0f;
        }
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, internal_format, W, H);
    const size_t slot = targets_.size();  // a target of its own, dropped afterwards
    bool same = false;
    try {
        {
            const PlainPixelStore unpack(PlainPixelStore::unpack);  // what a pass left would skew the upload
            glTextureSubImage2D(tex, 0, 0, 0, W, H, GL_RGBA, GL_FLOAT, pattern.data());
        }
        const Image cpu = box_downsample(read_texture(tex, W, H, 0, 4), factor);
        Image gpu = read_texture(sums(tex, w, h, factor, slot), w, h, 0, 4);
        divide_sums(gpu.pixels, factor);
        same = cpu.pixels.size() == gpu.pixels.size() &&
               std::memcmp(cpu.pixels.data(), gpu.pixels.data(), cpu.pixels.size() * sizeof(float)) == 0;
    } catch (const std::exception&) {  // cannot be read back as floats, or no program: the CPU filters
        same = false;
    }
    targets_.truncate(slot);
    glDeleteTextures(1, &tex);
    return same;
}

}  // namespace pathlet
