#include "frames/output_program.hpp"

#include <stdexcept>
#include <string>

namespace pathlet {

namespace {

constexpr const char* kVertex = R"(#version 450 core
void main() {  // one triangle over the viewport
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
)";

GLuint compile(GLenum stage, const char* src, const char* what) {
    GLuint s = glCreateShader(stage);
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(s, sizeof log, nullptr, log);
        glDeleteShader(s);
        throw std::runtime_error(std::string(what) + ": shader does not compile: " + log);
    }
    return s;
}

}  // namespace

GLuint link_output_program(const char* fragment, const char* what) {
    const GLuint vs = compile(GL_VERTEX_SHADER, kVertex, what);
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, fragment, what);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        glDeleteProgram(program);
        throw std::runtime_error(std::string(what) + ": program does not link: " + log);
    }
    return program;
}

void draw_output_program(GLuint program, GLuint vao, GLuint fbo, int w, int h, GLuint src, GLuint sampler) {
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_CULL_FACE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    glUseProgram(program);
    glBindTextureUnit(0, src);
    glBindSampler(0, sampler);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glBindSampler(0, 0);
    glBindTextureUnit(0, 0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

const OutputTargets::Target& OutputTargets::at(size_t slot, int w, int h) {
    if (targets_.size() <= slot) targets_.resize(slot + 1);
    Target& t = targets_[slot];
    if (t.w != w || t.h != h) {
        if (t.tex) {
            glDeleteFramebuffers(1, &t.fbo);
            glDeleteTextures(1, &t.tex);
        }
        glCreateTextures(GL_TEXTURE_2D, 1, &t.tex);
        glTextureStorage2D(t.tex, 1, format_, w, h);
        glCreateFramebuffers(1, &t.fbo);
        glNamedFramebufferTexture(t.fbo, GL_COLOR_ATTACHMENT0, t.tex, 0);
        t.w = w;
        t.h = h;
    }
    return t;
}

void OutputTargets::truncate(size_t n) {
    while (targets_.size() > n) {
        glDeleteFramebuffers(1, &targets_.back().fbo);
        glDeleteTextures(1, &targets_.back().tex);
        targets_.pop_back();
    }
}

}  // namespace pathlet
