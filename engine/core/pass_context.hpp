// The engine's side of a pass's PassContext (pathlet/pass.hpp): what one pass instance holds
// (its parameters, shader source, programs and bindings) and what it asks of the executor that
// runs it (PassHost). Private to the engine.
#pragma once

#include "graph/graph_model.hpp"
#include "pass_bindings.hpp"

#include <pathlet/buffer_texture.hpp>
#include <pathlet/pass.hpp>
#include <pathlet/shader.hpp>

#include <map>
#include <memory>
#include <stdexcept>
#include <string>

namespace pathlet {

class AsyncOutput;
class GpuScene;

struct PassError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct FrameInfo {
    uint64_t index = 0;
    double time = 0.0;
    Camera camera;
};

// "graph.json:/passes/3: pass 'lineao' (lineao)": how every error of a pass names it, with the
// graph file and the pass's place in it, as the compiler's errors do.
std::string pass_label(const CompiledGraph& g, const CompiledPass& p);

// What a pass's context needs from the executor that runs it.
class PassHost {
public:
    struct Physical {
        Texture tex;
        Buffer buf;
    };
    virtual const CompiledGraph& graph() const = 0;
    virtual const GpuScene& scene() const = 0;
    virtual const FrameInfo& frame() const = 0;
    virtual Physical& physical(int resource, bool previous) = 0;
    virtual GLuint framebuffer(const std::vector<GLuint>& color, GLuint depth, int mip, const std::string& pass) = 0;
    virtual GLuint empty_vertex_array() const = 0;
    virtual void stat(const std::string& pass, const std::string& name, double value) = 0;
    virtual void frame_incomplete(uint64_t frame) = 0;
    virtual AsyncOutput& pass_output() = 0;  // PassContext::write_image's files (the capture pass)
    // The units and binding points a pass's programs were given: what the reset between passes unbinds.
    virtual void used(const PassBindings& bindings, int uniform_blocks) = 0;

protected:
    ~PassHost() = default;
};

struct PassContextImpl {
    PassContextImpl(PassHost& host, int index, ShaderSource shaders);

    PassHost& host;
    int index;
    Params params;
    ShaderSource shaders;
    PassBindings bindings;
    std::map<std::string, std::unique_ptr<ShaderProgram>> programs;
    std::map<std::pair<std::string, GLenum>, BufferTexture> buffer_views;  // buffer_texture()

    const CompiledPass& pass() const { return host.graph().passes[size_t(index)]; }
    const Binding* binding(const std::string& pin) const;
    [[noreturn]] void unbound(const std::string& pin, const char* what) const;
    // The pass's parameters as the graph resolved them.
    void take_params() { params = Params(pass().name, pass().params, pass().type); }
    // Binds the texture pins its programs read (on their units) and its buffer pins (on their
    // binding points), before each execute().
    void bind_pins();
};

}  // namespace pathlet
