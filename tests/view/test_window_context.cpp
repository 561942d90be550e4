// The windowed context of `pathlet view`: GLFW asks for 4.5 core under a private Xvfb, the
// engine adopts it (same error capture as headless) and renders into the window.
#include "../support/optional_tool.hpp"
#include "../support/xvfb.hpp"
#include "gl_context.hpp"

#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <array>

using namespace pathlet;

namespace {
struct Window {
    GLFWwindow* w = nullptr;
    Window() {
        if (!glfwInit()) return;
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
        w = glfwCreateWindow(320, 180, "test", nullptr, nullptr);
        if (w) glfwMakeContextCurrent(w);
    }
    ~Window() {
        if (w) glfwDestroyWindow(w);
        glfwTerminate();
    }
};
}  // namespace

TEST(WindowContext, AdoptsGlfwCoreContextUnderXvfb) {
    PATHLET_REQUIRE_TOOLS("Xvfb");
    test::Xvfb x;
    ASSERT_TRUE(x.ok()) << "Xvfb did not start";
    Window win;
    ASSERT_NE(win.w, nullptr) << "GLFW could not create a 4.5 core window on " << x.display();
    auto ctx = GlContext::adopt_current("GLFW window");
    EXPECT_EQ(ctx->platform(), "GLFW window");
    EXPECT_NE(ctx->version().find("4.5"), std::string::npos) << ctx->version();
    EXPECT_FALSE(ctx->renderer().empty());

    // Errors land in the same capture as on the headless context.
    glBindTexture(0x1234, 0);
    auto errors = ctx->take_errors();
    ASSERT_FALSE(errors.empty()) << "debug output is not installed on the adopted context";
    EXPECT_FALSE(ctx->has_errors());

    // The window's own framebuffer takes engine GL calls (glvnd dispatch to the GLX context).
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(win.w, &fw, &fh);
    EXPECT_EQ(fw, 320);
    EXPECT_EQ(fh, 180);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    std::array<unsigned char, 4> px{};
    glReadPixels(10, 10, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    EXPECT_NEAR(px[0], 64, 1);
    EXPECT_NEAR(px[1], 128, 1);
    EXPECT_NEAR(px[2], 191, 1);
    EXPECT_TRUE(ctx->take_errors().empty());
}

TEST(WindowContext, NoCurrentContextIsAClearError) {
    try {
        GlContext::adopt_current("GLFW window");
        FAIL() << "expected GlError";
    } catch (const GlError& e) {
        EXPECT_NE(std::string(e.what()).find("no OpenGL context is current"), std::string::npos) << e.what();
    }
}
