// What the GL spec allows and a forgiving driver does not enforce, checked on the real GL stack:
// update barriers between shader writes and the clears or updates after them (the memory
// model's rule, gl_memory_model.hpp: llvmpipe shows no wrong pixel without them, a GPU may),
// storage blocks within GL_MAX_SHADER_STORAGE_BLOCK_SIZE (access beyond it is undefined), and a
// read-back whose buffer cannot be mapped (an error, never a lost count).
#include "frame_capture.hpp"
#include "gl_memory_model.hpp"
#include "shipped_graphs.hpp"

#include <pathlet/gpu_readback.hpp>
#include <pathlet/shader.hpp>

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

using namespace pathlet;

namespace {

std::string joined(const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += "\n  " + x;
    return s;
}

// A compute program that writes an image and a storage block, for the checker's own test.
const char* kWriter = R"(#version 450 core
layout(local_size_x = 1) in;
layout(r32f) uniform writeonly image2D u_out;
layout(std430, binding = 0) buffer Out { uint words[]; };
void main() { imageStore(u_out, ivec2(0), vec4(1.0)); words[0] = 1u; }
)";

GLuint compute_program() {
    const GLuint sh = glCreateShader(GL_COMPUTE_SHADER);
    glShaderSource(sh, 1, &kWriter, nullptr);
    glCompileShader(sh);
    const GLuint p = glCreateProgram();
    glAttachShader(p, sh);
    glLinkProgram(p);
    glDeleteShader(sh);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    EXPECT_TRUE(ok) << "the checker's test shader did not link";
    return p;
}

}  // namespace

// The checker itself: a clear after a dispatch that wrote, in a pass of its own, without the
// barrier is one violation per resource; with the barrier by the writer or by the clearer, none;
// a third pass's barrier in between does not count.
TEST(GlMemoryModel, TheCheckerSeesAClearOfShaderWrittenMemoryWithoutItsBarrier) {
    test_runtime();
    const GLuint prog = compute_program();
    GLuint tex = 0, buf = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_R32F, 1, 1);
    glCreateBuffers(1, &buf);
    glNamedBufferStorage(buf, 16, nullptr, GL_DYNAMIC_STORAGE_BIT);
    const float zero = 0.0f;
    auto write = [&] {  // as a pass named "writer" would
        glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 1, -1, "writer");
        glUseProgram(prog);
        glBindImageTexture(0, tex, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buf);
        glDispatchCompute(1, 1, 1);
        glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
        glPopDebugGroup();
    };
    auto in_pass = [&](const char* name, GLbitfield barrier, bool clear) {
        glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 2, -1, name);
        if (barrier) glMemoryBarrier(barrier);
        if (clear) {
            glClearTexImage(tex, 0, GL_RED, GL_FLOAT, &zero);
            glClearNamedBufferData(buf, GL_R32F, GL_RED, GL_FLOAT, &zero);
        }
        glPopDebugGroup();
    };
    gl_memory_model::reset();
    write();
    in_pass("clearer", 0, true);
    ASSERT_TRUE(gl_memory_model::active()) << "the interposer is not in the executable (ENABLE_EXPORTS)";
    EXPECT_EQ(gl_memory_model::take_violations().size(), 2u) << "the texture and the buffer";
    write();
    in_pass("clearer", GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT, true);
    EXPECT_EQ(joined(gl_memory_model::take_violations()), "") << "the clearer's own barrier";
    write();
    in_pass("third", GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT, false);
    in_pass("clearer", 0, true);
    EXPECT_EQ(gl_memory_model::take_violations().size(), 2u) << "a third pass's barrier is luck, not a guarantee";
    glDeleteTextures(1, &tex);
    glDeleteBuffers(1, &buf);
    glDeleteProgram(prog);
}

// Every shipped graph, three frames (what one frame's shaders wrote is cleared by the next):
// every clear or update of shader-written memory behind its update barrier.
TEST(GlMemoryModel, EveryShippedGraphClearsWhatShadersWroteOnlyBehindAnUpdateBarrier) {
    test_runtime();
    for (const ShippedGraph& g : shipped_graphs()) {
        if (const std::string why = g.unsupported_here(); !why.empty()) {
            std::printf("skipped %s: %s\n", g.name.c_str(), why.c_str());
            continue;
        }
        RenderOptions opt;
        opt.graph_path = g.path;
        opt.size = {160, 90};
        opt.time = {2.0, 2.08, 0.04};  // the middle of the small phantom's 0..4 s
        opt.warmup = 0;
        opt.write_images = false;
        opt.quiet = true;
        gl_memory_model::reset();
        render(test_runtime(), small_phantom_scene(), opt);
        EXPECT_EQ(joined(gl_memory_model::take_violations()), "") << g.name;
    }
}

// MLAB's nodes at 1920x1080 with 8 layers: 142 MiB in one storage block, above GL 4.5's minimum
// block size (128 MiB, llvmpipe's too): refused in setup, naming the size and the picture, on
// every driver (before the interlock llvmpipe lacks is asked for).
TEST(StorageBlocks, MlabNodesBeyondTheBlockSizeAreRefusedNamingSizeAndPicture) {
    struct Minimum {
        Minimum() { ::setenv("PATHLET_GL_LIMITS", "minimum", 1); }
        ~Minimum() { ::unsetenv("PATHLET_GL_LIMITS"); }
    } minimum;
    RenderOptions opt;
    opt.graph_path = std::string(PATHLET_SOURCE_DIR) + "/graphs/variant2_mlabdb.json";
    opt.size = {1920, 1080};
    opt.sets = {"blend.layers=8"};
    opt.time.start = 2.0;
    opt.warmup = 0;
    opt.write_images = false;
    opt.quiet = true;
    try {
        render(test_runtime(), small_phantom_scene(), opt);
        FAIL() << "MLAB's 142 MiB of nodes were accepted";
    } catch (const std::exception& e) {
        const std::string m = e.what();
        for (const char* part : {"mlab_blend's nodes", "142.4 MiB", "1920x1080", "128.0 MiB",
                                 "GL_MAX_SHADER_STORAGE_BLOCK_SIZE"})
            EXPECT_NE(m.find(part), std::string::npos) << "'" << part << "' missing: " << m;
    }
    opt.sets = {"blend.layers=7"};  // 127 MiB fits: then only the interlock can stop it here
    try {
        render(test_runtime(), small_phantom_scene(), opt);
    } catch (const std::exception& e) {
        EXPECT_EQ(std::string(e.what()).find("storage block"), std::string::npos) << e.what();
    }
}

// A buffer the driver cannot map: GpuReadback says so when it makes its ring, instead of
// handing out nothing (a lost count) or copying from null.
TEST(GpuReadbackMaps, AFailedMapIsAnErrorNamingIt) {
    test_runtime();
    gl_memory_model::fail_buffer_maps(true);
    try {
        GpuReadback rb(16);
        ADD_FAILURE() << "a read-back ring without a mapped buffer was made";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("glMapNamedBufferRange"), std::string::npos) << e.what();
    }
    gl_memory_model::fail_buffer_maps(false);
    GpuReadback rb(16);  // and with the map back, as always
    EXPECT_EQ(rb.slots(), 4u);
}
