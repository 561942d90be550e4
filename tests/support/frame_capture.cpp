#include "frame_capture.hpp"
#include "phantom/phantom.hpp"

#include "executor.hpp"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <unistd.h>
#include <fstream>

namespace pathlet {

Runtime& test_runtime(const std::vector<std::string>& plugin_dirs) {
    static Runtime* rt = [&] {
        auto* r = new Runtime;
        r->load_plugins(plugin_dirs);
        r->ensure_gl(true);
        return r;
    }();
    return *rt;
}

namespace {
// GL rows are bottom-up; Image rows top-down.
template <class T>
Image flip_into_image(const std::vector<T>& raw, int w, int h) {
    Image img;
    img.width = w;
    img.height = h;
    img.channels = 1;
    img.is_float = true;
    img.pixels.resize(raw.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img.at(x, y, 0) = float(raw[size_t(h - 1 - y) * size_t(w) + size_t(x)]);
    return img;
}
}  // namespace

Image read_resource(const Texture& t) {
    const size_t n = size_t(t.width) * size_t(t.height);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    if (t.internal_format == GL_DEPTH_COMPONENT24 || t.internal_format == GL_DEPTH_COMPONENT32F) {
        std::vector<float> raw(n);
        glGetTextureImage(t.id, 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(n * sizeof(float)), raw.data());
        return flip_into_image(raw, t.width, t.height);
    }
    if (t.internal_format == GL_R32I) {
        std::vector<GLint> raw(n);
        glGetTextureImage(t.id, 0, GL_RED_INTEGER, GL_INT, GLsizei(n * sizeof(GLint)), raw.data());
        Image img = flip_into_image(raw, t.width, t.height);
        img.is_float = false;
        return img;
    }
    return read_texture(t.id, t.width, t.height, 0, t.internal_format == GL_R32F ? 1 : 4);
}

Frame render_frame(Runtime& rt, const Scene& scene, RenderOptions opt, const std::vector<std::string>& names) {
    opt.time.end = opt.time.start;
    opt.warmup = 0;
    opt.write_images = false;
    opt.quiet = true;
    opt.keep.insert(opt.keep.end(), names.begin(), names.end());  // read after the frame: not pooled
    Frame f;
    RenderResult res = render(rt, scene, opt, [&](const Executor& ex, size_t) {
        for (const auto& n : names) f.tex[n] = read_resource(ex.texture(n));
    });
    for (const auto& p : res.profiler.passes())
        for (const auto& [k, v] : p.stats) f.stats[k] = v;
    if (opt.camera_path.empty()) f.camera = frame_bounds(scene.bounds(), opt.size);
    return f;
}

const Scene& small_phantom_scene() {
    static const Scene s = phantom::make_phantom(phantom::phantom_preset("small"), {});
    return s;
}

const Scene& helix_bundle_scene() {
    static const Scene scene = [] {
        Scene s;
        Pathlines& pl = s.lines;
        auto add = [&](auto pos, auto vel) {
            LineRange r{uint32_t(pl.position.size()), 101};
            for (int k = 0; k <= 100; ++k) {
                double t = 0.1 * k;
                pl.position.push_back(pos(t));
                pl.velocity.push_back(vel(t));
                pl.time.push_back(float(t));
            }
            pl.lines.push_back(r);
        };
        for (int i = 0; i < 40; ++i) {
            double radius = 1.0 + 0.6 * (i % 4), phase = 2.39996 * i, w = 0.8;
            double gain = 0.3 + 0.7 * double(i % 7) / 6.0;
            add([=](double t) { return glm::vec3(4 * t, radius * std::cos(w * t + phase), radius * std::sin(w * t + phase)); },
                [=](double t) {
                    double f = gain * (0.6 + 0.4 * std::sin(0.7 * t + i));
                    return glm::vec3(4 * f, -radius * w * std::sin(w * t + phase) * f, radius * w * std::cos(w * t + phase) * f);
                });
        }
        add([](double t) { return glm::vec3(4 * t, 12 + 0.5 * std::sin(0.5 * t), 0); },
            [](double t) { return glm::vec3(6, 0.375 * std::cos(0.5 * t), 0); });
        s.source = "synthetic helix bundle (tests/support)";
        s.lines.units = {"mm", "s", "mm/s"};
        return s;
    }();
    return scene;
}

const std::string& test_scratch_dir(const std::string& prefix) {
    static const std::string dir = [&] {
        namespace fs = std::filesystem;
        fs::path p = fs::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()));
        fs::create_directories(p);
        struct Cleanup : ::testing::Environment {
            fs::path dir;
            explicit Cleanup(fs::path d) : dir(std::move(d)) {}
            void TearDown() override { fs::remove_all(dir); }
        };
        ::testing::AddGlobalTestEnvironment(new Cleanup(p));
        return p.string();
    }();
    return dir;
}

const Scene& two_speed_lines_scene() {
    static const Scene scene = [] {
        Scene s;
        auto add = [&](float x0, float speed, float y) {
            LineRange r{uint32_t(s.lines.position.size()), 201};
            for (int k = 0; k <= 200; ++k) {
                float t = 0.05f * float(k);
                s.lines.position.push_back({x0 + speed * t, y, 0.0f});
                s.lines.velocity.push_back({speed, 0.0f, 0.0f});
                s.lines.time.push_back(t);
            }
            s.lines.lines.push_back(r);
        };
        add(-15.0f, 4.0f, 0.0f);
        add(0.0f, 1.0f, 4.0f);
        s.source = "two straight pathlets, fast and slow (tests/support)";
        s.lines.units = {"mm", "s", "mm/s"};  // as the phantom's: the overlay shows them
        return s;
    }();
    return scene;
}

std::string write_square_on_camera(const std::string& path) {
    std::ofstream(path) << R"({"keyframes": [{"time": 0, "eye": [5, 2, 60], "target": [5, 2, 0], "up": [0, 1, 0], "fov": 20}]})";
    return path;
}

float square_on_pixels_per_unit(int height) { return 0.5f * float(height) / (60.0f * std::tan(glm::radians(10.0f))); }

}  // namespace pathlet
