#include "camera.hpp"

#include <gtest/gtest.h>

using namespace pathlet;

TEST(Camera, FrameBoundsKeepsEveryCornerOnScreen) {
    Bounds b{{-10, -40, 0}, {30, 20, 90}};
    Camera c = frame_bounds(b, {1280, 720});
    for (int i = 0; i < 8; ++i) {
        glm::vec3 p(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
        glm::vec4 clip = c.proj * c.view * glm::vec4(p, 1);
        glm::vec3 ndc = glm::vec3(clip) / clip.w;
        EXPECT_LE(std::abs(ndc.x), 1.0f);
        EXPECT_LE(std::abs(ndc.y), 1.0f);
        EXPECT_GT(clip.w, c.near_plane * 0.99f);
        EXPECT_LT(clip.w, c.far_plane * 1.01f);
    }
    // Looks along the thinnest axis (x here).
    glm::vec3 dir = glm::normalize(c.target - c.eye);
    EXPECT_NEAR(std::abs(dir.x), 1.0f, 1e-5f);
}

TEST(Camera, OrbitFullTurnReturnsToStart) {
    Bounds b{{-1, -1, -1}, {1, 1, 1}};
    Camera c = frame_bounds(b, {64, 64});
    Camera o = orbit(c, 90.0, 4.0, b, {64, 64});  // 360 degrees
    EXPECT_NEAR(glm::length(o.eye - c.eye), 0.0f, 1e-4f);
    Camera q = orbit(c, 90.0, 1.0, b, {64, 64});
    EXPECT_NEAR(glm::length(q.eye - q.target), glm::length(c.eye - c.target), 1e-4f);
    EXPECT_GT(glm::length(q.eye - c.eye), 0.1f);
}

TEST(CameraPath, InterpolatesThroughKeyframes) {
    auto p = CameraPath::parse(R"({"keyframes":[
        {"time":0,"eye":[0,-10,0],"target":[0,0,0],"up":[0,0,1],"fov":40},
        {"time":2,"eye":[10,0,0],"target":[0,0,0],"fov":60}]})",
                               "cam.json");
    Bounds b{{-1, -1, -1}, {1, 1, 1}};
    EXPECT_NEAR(glm::length(p.at(0, b, {64, 64}).eye - glm::vec3(0, -10, 0)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(p.at(2, b, {64, 64}).eye - glm::vec3(10, 0, 0)), 0.0f, 1e-5f);
    EXPECT_NEAR(p.at(1, b, {64, 64}).fov_y_deg, 50.0f, 1e-4f);
    EXPECT_NEAR(glm::length(p.at(99, b, {64, 64}).eye - glm::vec3(10, 0, 0)), 0.0f, 1e-5f);  // clamped
}

TEST(CameraPath, BadFilesNameTheFileAndPointer) {
    auto err = [](const std::string& text) {
        try {
            CameraPath::parse(text, "cam.json");
        } catch (const DataError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(err("{").find("cam.json:1:2: not valid JSON (camera path)"), std::string::npos) << err("{");
    EXPECT_NE(err(R"({"keyframes":[]})").find("cam.json:/keyframes"), std::string::npos);
    EXPECT_NE(err(R"({"keyframes":[{"time":0,"target":[0,0,0]}]})").find("/keyframes/0/eye: missing"),
              std::string::npos);
    EXPECT_NE(err(R"({"keyframes":[{"time":1,"eye":[1,0,0],"target":[0,0,0]},{"time":1,"eye":[2,0,0],"target":[0,0,0]}]})")
                  .find("/keyframes/1/time: keyframe times must increase"),
              std::string::npos);
    EXPECT_NE(err(R"({"keyframes":[{"time":0,"eye":[1,0,0],"target":[0,0,0],"fov":500}]})").find("/fov"),
              std::string::npos);
}
