// Shared by the engine tests: a runtime with the built-in plugins, a tiny scene, and a
// one-call render that hands back a texture.
#pragma once

#include "executor.hpp"
#include "image_io.hpp"
#include "renderer.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace pathlet::testing_util {

inline std::string source(const std::string& rel) { return std::string(PATHLET_SOURCE_DIR) + "/" + rel; }
inline std::string test_file(const std::string& rel) { return std::string(PATHLET_TEST_SOURCE_DIR) + "/" + rel; }

// One process-wide runtime (never destroyed: creating GL contexts again and again is slow on
// llvmpipe, and Runtime is not movable because its plugin host refers to its registry).
inline Runtime& runtime() {
    static Runtime* rt = [] {
        ::setenv("PATHLET_SHADER_PATH", (std::string(PATHLET_TEST_SOURCE_DIR) + "/shaders").c_str(), 1);
        auto* r = new Runtime();
        r->load_plugins({});
        r->ensure_gl(true);
        return r;
    }();
    return *rt;
}

inline Scene tiny_scene() {
    Scene s;
    s.source = "tiny";
    for (int l = 0; l < 2; ++l) {
        LineRange r{uint32_t(s.lines.position.size()), 5};
        for (int k = 0; k < 5; ++k) {
            s.lines.position.push_back({float(k), float(l), 0.0f});
            s.lines.time.push_back(float(k));
            s.lines.velocity.push_back({1.0f, 0.0f, 0.0f});
        }
        s.lines.lines.push_back(r);
    }
    return s;
}

// Renders `graph` once (or `frames` times) and returns the given resource of the last frame.
inline Image render_resource(const std::string& graph, const std::string& resource, glm::ivec2 size,
                             std::vector<std::string> sets = {}, int frames = 1) {
    Scene scene = tiny_scene();
    RenderOptions o;
    o.graph_path = graph;
    o.size = size;
    o.sets = std::move(sets);
    o.warmup = 0;
    o.write_images = false;
    o.quiet = true;
    o.time.start = 0;
    o.time.end = double(frames - 1);
    o.time.step = 1;
    Image out;
    render(runtime(), scene, o, [&](const Executor& e, size_t) {
        Texture t = e.texture(resource);
        out = read_texture(t.id, t.width, t.height, 0, 4);
    });
    return out;
}

}  // namespace pathlet::testing_util
