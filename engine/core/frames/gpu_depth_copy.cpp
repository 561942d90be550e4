#include "frames/gpu_depth_copy.hpp"

#include "frames/output_program.hpp"
#include "image_io.hpp"
#include "pixel_store.hpp"

#include <cstdint>
#include <cstring>
#include <random>

namespace pathlet {

namespace {

// Two ways to a float, measured per format: texelFetch's own value (mode 0), or a normalised
// depth (depth16, depth24) taken back to its integer and divided as a CPU pixel path divides it,
// in double precision rounded once to float (mode 1: for drivers whose texelFetch is a
// single-precision product). The integer comes back exactly from any float within half a step.
constexpr const char* kDepthCopyFragment = R"(#version 450 core
layout(binding = 0) uniform sampler2D u_depth;
uniform double u_steps;  // 2^bits - 1; 0: texelFetch's value as it is
layout(location = 0) out float o_depth;
void main() {
    float d = texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).r;
    if (u_steps == 0.0lf) {
        o_depth = d;
    } else {
        double i = floor(double(d) * u_steps + 0.5lf);
        o_depth = float(i * (1.0lf / u_steps));
    }
}
)";

double steps_of(GLenum depth_format) {
    if (depth_format == GL_DEPTH_COMPONENT16) return 65535.0;
    if (depth_format == GL_DEPTH_COMPONENT24) return 16777215.0;
    return 0.0;
}

}  // namespace

GpuDepthCopy::~GpuDepthCopy() {
    if (vao_) glDeleteVertexArrays(1, &vao_);
    if (sampler_) glDeleteSamplers(1, &sampler_);
    if (program_) glDeleteProgram(program_);
}

GLuint GpuDepthCopy::to_float(GLuint src, GLenum depth_format, int w, int h, size_t slot) {
    if (!program_) {
        program_ = link_output_program(kDepthCopyFragment, "GPU depth copy");
        steps_loc_ = glGetUniformLocation(program_, "u_steps");
        glCreateVertexArrays(1, &vao_);
        // A pass may have set its depth texture to compare (a shadow lookup): plain depth here.
        glCreateSamplers(1, &sampler_);
        glSamplerParameteri(sampler_, GL_TEXTURE_COMPARE_MODE, GL_NONE);
        glSamplerParameteri(sampler_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glSamplerParameteri(sampler_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    const OutputTargets::Target& t = targets_.at(slot, w, h);
    const auto it = exact_.find(depth_format);  // mode 1 only where measured so
    const bool redivide = it != exact_.end() && it->second == 1;
    glProgramUniform1d(program_, steps_loc_, redivide ? steps_of(depth_format) : 0.0);
    draw_output_program(program_, vao_, t.fbo, w, h, src, sampler_);
    return t.tex;
}

bool GpuDepthCopy::exact(GLenum depth_format) {
    auto it = exact_.find(depth_format);
    if (it == exact_.end()) {
        it = exact_.emplace(depth_format, 0).first;  // what to_float() uses while measuring
        if (!measure(depth_format)) {
            it->second = 1;
            if (steps_of(depth_format) == 0.0 || !measure(depth_format)) it->second = -1;
        }
    }
    return it->second >= 0;
}

bool GpuDepthCopy::measure(GLenum depth_format) {
    // 256 x 256: every depth16 value once; for the wider formats the ends, values next to them,
    // and random bit patterns (depth24's low 8 bits of a 32-bit upload are dropped).
    const int w = 256, h = 256;
    const size_t n = size_t(w) * size_t(h);
    std::mt19937 rng(4321);
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, depth_format, w, h);
    const size_t slot = targets_.size();  // a target of its own, dropped afterwards
    bool same = false;
    try {
        {
            const PlainPixelStore unpack(PlainPixelStore::unpack);
            if (depth_format == GL_DEPTH_COMPONENT16) {
                std::vector<uint16_t> v(n);
                for (size_t i = 0; i < n; ++i) v[i] = uint16_t(i);
                glTextureSubImage2D(tex, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT, v.data());
            } else if (depth_format == GL_DEPTH_COMPONENT32F) {
                std::uniform_real_distribution<float> unit(0.0f, 1.0f);
                std::vector<float> v(n);
                for (size_t i = 0; i < n; ++i) v[i] = i < 4 ? float(i) / 3.0f : unit(rng);
                v[4] = 1e-40f;  // a denormal
                glTextureSubImage2D(tex, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, v.data());
            } else {
                std::vector<uint32_t> v(n);
                for (size_t i = 0; i < n; ++i) v[i] = i < 512 ? (i < 256 ? uint32_t(i) << 8 : ~0u - (uint32_t(i - 256) << 8)) : rng();
                glTextureSubImage2D(tex, 0, 0, 0, w, h, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, v.data());
            }
        }
        const Image direct = read_texture(tex, w, h, 0, 1);
        const Image copied = read_texture(to_float(tex, depth_format, w, h, slot), w, h, 0, 1);
        same = direct.pixels.size() == n && copied.pixels.size() == n &&
               std::memcmp(direct.pixels.data(), copied.pixels.data(), n * sizeof(float)) == 0;
    } catch (const std::exception&) {  // no program or no read: the depth is read as it is
        same = false;
    }
    targets_.truncate(slot);
    glDeleteTextures(1, &tex);
    return same;
}

}  // namespace pathlet
