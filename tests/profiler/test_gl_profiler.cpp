// Parts that need a real context: the profiler's backends timing glClear work, and texture
// read-back. Skipped (with the reason) where no EGL context can be made.
#include "gl_context.hpp"
#include "image_io.hpp"
#include "image_probes.hpp"
#include "profiler/profiler.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace pathlet {
namespace {

class GlTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        try {
            gl = GlContext::create_headless();
        } catch (const std::exception& e) {
            why = e.what();
        }
    }
    static void TearDownTestSuite() { gl.reset(); }
    void SetUp() override {
        // GL is no optional tool: every GL test needs a context (llvmpipe without a GPU).
        if (!gl) FAIL() << "no GL context: " << why;
    }
    void TearDown() override {
        if (gl)
            for (const auto& e : gl->take_errors()) ADD_FAILURE() << "GL: " << e;
    }
    static inline std::unique_ptr<GlContext> gl;
    static inline std::string why;
};

// A float render target that frames clear repeatedly: real rasterisation work for llvmpipe.
struct ClearTarget {
    GLuint tex = 0, fbo = 0;
    explicit ClearTarget(int size) {
        glCreateTextures(GL_TEXTURE_2D, 1, &tex);
        glTextureStorage2D(tex, 1, GL_RGBA32F, size, size);
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    }
    ~ClearTarget() {
        glDeleteFramebuffers(1, &fbo);
        glDeleteTextures(1, &tex);
    }
    void clear(int times) const {
        for (int i = 0; i < times; ++i) {
            const float c[4] = {float(i % 7) / 7.0f, 0.5f, 0.25f, 1.0f};
            glClearNamedFramebufferfv(fbo, GL_COLOR, 0, c);
        }
    }
};

void profile_frames(Profiler& p, const ClearTarget& target, int frames) {
    for (int f = 0; f < frames; ++f) {
        p.begin_frame(uint64_t(f));
        p.begin_pass("clear");
        target.clear(20);
        p.end_pass();
        p.begin_pass("empty");
        p.end_pass();
        p.end_frame();
    }
}

TEST_F(GlTest, FinishBackendTimesClearWork) {
    ClearTarget target(512);
    Profiler p;
    p.set_warmup_frames(2);
    p.init(is_software_renderer(gl->renderer()) ? TimingBackend::Auto : TimingBackend::CpuFinish, gl->renderer());
    ASSERT_EQ(p.backend(), TimingBackend::CpuFinish) << p.backend_description();
    profile_frames(p, target, 6);

    auto passes = p.passes();
    ASSERT_EQ(passes.size(), 2u);
    const Profiler::PassResult& clear = passes[0];
    EXPECT_EQ(clear.gpu_ms.n, 4u);
    EXPECT_GT(clear.gpu_ms.median, 0.0);
    // The finish-bracketed time contains the recording time of the same pass.
    EXPECT_GE(clear.gpu_ms.median, clear.cpu_ms.median);
    EXPECT_GE(p.frame_ms().median, clear.gpu_ms.median);
    EXPECT_LT(passes[1].gpu_ms.median, clear.gpu_ms.median);
    const std::string table = p.table("glClear x20 @ 512^2 on " + gl->renderer());
    EXPECT_NE(table.find("glFinish"), std::string::npos) << table;
    std::printf("%s", table.c_str());
}

TEST_F(GlTest, TimestampBackendCollectsWithoutStalling) {
    ClearTarget target(256);
    Profiler p;
    p.set_warmup_frames(2);
    p.init(TimingBackend::GlTimestamp, gl->renderer());
    ASSERT_EQ(p.backend(), TimingBackend::GlTimestamp) << p.backend_description();
    if (is_software_renderer(gl->renderer())) {
        EXPECT_NE(p.backend_description().find("WARNING"), std::string::npos) << p.backend_description();
    }
    // llvmpipe lags several frames behind here: the ring must grow, not drop (a fixed ring
    // of 4 lost 8 of these 12 frames).
    profile_frames(p, target, 12);
    p.flush();
    EXPECT_EQ(p.frames_recorded(), 12u);
    EXPECT_EQ(p.gpu_frames_dropped(), 0u);
    const Profiler::Stats frame = p.frame_ms();
    EXPECT_EQ(frame.n, 10u);
    EXPECT_GE(frame.min, 0.0);
    EXPECT_LE(frame.max, p.frame_cpu_ms().max + 1000.0);
    for (const auto& r : p.passes()) {
        EXPECT_LE(r.gpu_ms.n, 10u);
        EXPECT_EQ(r.cpu_ms.n, 10u);
        if (r.gpu_ms.n) {
            EXPECT_GT(r.gpu_ms.min, 0.0) << r.name;  // zeros are discarded
        }
    }
    std::printf("%s", p.table("GL timestamps (" + gl->renderer() + ")").c_str());
    p.release_gl();
}

TEST_F(GlTest, ReadTextureFlipsRowsToTopFirst) {
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 2, GL_RGBA32F, 8, 4);
    const float grey[4] = {0.25f, 0.5f, 0.75f, 1.0f}, red[4] = {1, 0, 0, 1};
    glClearTexImage(tex, 0, GL_RGBA, GL_FLOAT, grey);
    glClearTexSubImage(tex, 0, 0, 0, 0, 8, 1, 1, GL_RGBA, GL_FLOAT, red);  // GL row 0 = bottom
    glClearTexImage(tex, 1, GL_RGBA, GL_FLOAT, red);

    Image img = read_texture(tex, 8, 4);
    EXPECT_TRUE(img.is_float);
    EXPECT_EQ(count_pixels_equal(img, {0.25f, 0.5f, 0.75f, 1.0f}, 0.0f), 24u);
    for (int x = 0; x < 8; ++x) EXPECT_EQ(img.at(x, 3, 0), 1.0f) << "bottom row last";
    EXPECT_EQ(img.at(0, 0, 0), 0.25f);

    Image r = read_texture(tex, 8, 4, 0, 1);
    EXPECT_EQ(r.channels, 1);
    EXPECT_EQ(r.at(0, 3, 0), 1.0f);
    EXPECT_EQ(r.at(0, 0, 0), 0.25f);

    Image mip = read_texture(tex, 4, 2, 1);
    EXPECT_EQ(count_pixels_equal(mip, {1, 0, 0, 1}), 8u);
    EXPECT_THROW(read_texture(tex, 8, 8), std::runtime_error);  // wrong size is caught, not overrun
    glDeleteTextures(1, &tex);
}

}  // namespace
}  // namespace pathlet
