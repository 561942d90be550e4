#include "view/viewer.hpp"

#include "gl_context.hpp"
#include "view/view_loop.hpp"
#include "view/view_session.hpp"

#include <pathlet/gpu_scene.hpp>

#include <cstdio>

namespace pathlet::view {

Viewer::Viewer(const ViewSettings& settings) : settings_(settings) {
    if (!settings_.script.empty()) script_ = load_script(settings_.script);
    window_.open(settings_.size, /*vsync=*/settings_.script.empty(), &input_, install_input_callbacks);
}

int Viewer::run(Runtime& rt, const Scene& scene, const std::string& graph_path, const std::vector<std::string>& sets) {
    rt.gl = GlContext::adopt_current("GLFW window");
    std::fprintf(stderr, "%s\n", rt.gl->summary().c_str());
    window_.open_ui();
    // The graph: compiled and set up once (as render does); changed in place afterwards.
    GpuScene gpu;
    gpu.upload(scene);
    ViewSession session(rt, gpu, settings_.size, graph_path, sets);
    ViewLoop loop(settings_, window_, input_, rt, session, scene, std::move(script_));
    std::fprintf(stderr, "%s", kKeysHelp);
    while (loop.running()) {
        loop.input();
        loop.frame();
        loop.present();
    }
    return loop.finish();
}

}  // namespace pathlet::view
