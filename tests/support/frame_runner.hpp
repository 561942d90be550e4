// A graph driven frame by frame on real GL (llvmpipe): the executor kept between frames
// (temporal state), parameters changed between frames as the viewer changes them
// (Executor::reparam), buffers and textures read back after a frame.
#pragma once

#include "camera.hpp"
#include "executor.hpp"
#include "frame_capture.hpp"
#include "graph/graph_model.hpp"

#include <pathlet/gpu_scene.hpp>

#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlet {

class FrameRunner {
public:
    // `keep`: resources read after a frame (kept out of the pool).
    FrameRunner(const std::string& graph, const std::vector<std::string>& sets, const Scene& scene, glm::ivec2 size,
        const Camera& camera, const std::vector<std::string>& keep)
        : camera_(camera) {
        Runtime& rt = test_runtime();
        GraphFile g = rt.load_graph(graph, sets);
        for (auto& r : g.resources)
            for (const auto& k : keep)
                if (r.name == k) r.persistent = true;
        cg_ = compile_graph(g, rt.registry, size);
        gpu_.upload(scene);
        ex_ = std::make_unique<Executor>(*rt.gl, cg_, gpu_);
        ex_->setup();
    }
    void frame(double t) { ex_->run_frame({index_++, t, camera_}); }
    // A pass parameter, as the viewer changes it between frames.
    void set(const std::string& pass, const std::string& param, const json& value) {
        for (size_t i = 0; i < cg_.passes.size(); ++i)
            if (cg_.passes[i].name == pass) {
                cg_.passes[i].params[param] = value;
                ex_->reparam(i);
                return;
            }
        throw std::invalid_argument("no pass " + pass);
    }
    std::vector<uint32_t> words(const std::string& resource) const {
        const Buffer b = ex_->buffer(resource);
        std::vector<uint32_t> v(b.bytes / 4);
        glGetNamedBufferSubData(b.id, 0, GLsizeiptr(v.size() * 4), v.data());
        return v;
    }
    Image texture(const std::string& resource) const { return read_resource(ex_->texture(resource)); }
    const Executor& executor() const { return *ex_; }

private:
    Camera camera_;
    CompiledGraph cg_;
    GpuScene gpu_;
    std::unique_ptr<Executor> ex_;
    uint64_t index_ = 0;
};

// A camera looking down -z at `target` from `distance` (fovy in degrees), near/far fitted.
inline Camera camera_down_z(const Scene& scene, glm::vec3 target, float distance, float fov, glm::ivec2 size) {
    Camera c;
    c.eye = target + glm::vec3(0.0f, 0.0f, distance);
    c.target = target;
    c.up = {0.0f, 1.0f, 0.0f};
    c.fov_y_deg = fov;
    finish_camera(c, scene.bounds(), size);
    return c;
}

}  // namespace pathlet
