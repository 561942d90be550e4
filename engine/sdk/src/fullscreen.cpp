// Fullscreen passes with a fragment and a compute version: the `impl` parameter, the rule
// `auto` follows, and the dispatch over a pixel rectangle (the compute twin of
// draw_fullscreen and draw_fullscreen_on_geometry).
#include <pathlet/pass.hpp>
#include <pathlet/shader.hpp>

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace pathlet {

std::string software_rasterizer(const std::string& gl_renderer) {
    // GL_RENDERER of Mesa's llvmpipe ("llvmpipe (LLVM 15.0.6, 256 bits)", also under zink),
    // softpipe and the classic swrast ("Software Rasterizer"), SwiftShader, and Windows' WARP.
    static const char* const kNames[] = {"llvmpipe", "softpipe", "swrast", "Software Rasterizer", "SwiftShader",
                                         "Microsoft Basic Render Driver"};
    std::string lower = gl_renderer;
    for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const char* name : kNames) {
        std::string n = name;
        for (char& c : n) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (lower.find(n) != std::string::npos) return name;
    }
    return "";
}

FullscreenImpl auto_impl(const std::string& gl_renderer) {
    return software_rasterizer(gl_renderer).empty() ? FullscreenImpl::compute : FullscreenImpl::fragment;
}

PassTypeBuilder& PassTypeBuilder::compute_version() {
    return param_enum("impl", "auto", {"auto", "fragment", "compute"},
                      "which version runs: auto = compute on a GPU, fragment on a software rasterizer (llvmpipe), "
                      "where it is the faster; the two give the same picture");
}

bool PassContext::use_compute() const {
    const PassTypeInfo* type = params().type();
    if (type && !type->param("impl"))
        throw std::logic_error("pass '" + pass_name() + "' asked for its compute version, but its type '" + type->type +
                               "' declares none (PassTypeBuilder::compute_version())");
    const std::string impl = params().s("impl");
    if (impl == "compute") return true;
    if (impl == "fragment") return false;
    const GLubyte* r = glGetString(GL_RENDERER);
    return auto_impl(r ? reinterpret_cast<const char*>(r) : "") == FullscreenImpl::compute;
}

ShaderProgram& PassContext::fullscreen_program(const std::string& file, std::vector<std::string> defines) {
    if (!use_compute()) return program({"fullscreen.vert", file}, defines);
    defines.push_back("FULLSCREEN_COMPUTE");
    return program_from({{GL_COMPUTE_SHADER, {shaders().find(file)}}}, defines);
}

void PassContext::dispatch_fullscreen(ShaderProgram& prog, const std::string& depth_pin) {
    const glm::ivec2 size = output_size();
    dispatch_fullscreen(prog, glm::ivec4(0, 0, size.x, size.y), depth_pin);
}

void PassContext::dispatch_fullscreen(ShaderProgram& prog, glm::ivec4 rect, const std::string& depth_pin) {
    const glm::ivec3 group = prog.local_size();
    if (group.x <= 0)
        throw std::logic_error("pass '" + pass_name() + "': dispatch_fullscreen needs a compute program "
                               "(fullscreen_program() with impl = compute)");
    const glm::ivec2 extent = glm::max(glm::ivec2(rect.z - rect.x, rect.w - rect.y), glm::ivec2(0));
    if (extent.x == 0 || extent.y == 0) return;
    prog.use();
    prog.set("u_fullscreen_rect", rect);
    const bool on_geometry = !depth_pin.empty();
    prog.set("u_fullscreen_on_geometry", on_geometry ? 1 : 0);
    if (on_geometry) prog.bind_texture("u_fullscreen_depth", texture(depth_pin).id);
    glDispatchCompute(GLuint((extent.x + group.x - 1) / group.x), GLuint((extent.y + group.y - 1) / group.y), 1);
    // Image stores are incoherent: whatever reads the output next (a sampler, a framebuffer,
    // glCopyImageSubData, a read-back) must wait for them. One barrier per dispatch.
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

}  // namespace pathlet
