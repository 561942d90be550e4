// vignette: darkens an image towards its corners. A template for your own pass: declare
// parameters and pins once in the builder, compile programs in setup(), draw in execute().
// The declaration binds: `strength` and `radius` reach vignette.frag's u_strength and u_radius,
// the input `src` its sampler u_src.
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

namespace {

class Vignette : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        // "fullscreen.vert" comes from the engine's shared shaders, "vignette.frag" from this
        // plugin's folder (installed beside vignette.so as vignette/vignette.frag).
        prog_ = &ctx.program({"fullscreen.vert", "vignette.frag"});
    }
    void execute(pathlet::PassContext& ctx) override {
        ctx.bind_framebuffer({"dst"});
        prog_->use();
        ctx.draw_fullscreen();
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
};

}  // namespace

PATHLET_PLUGIN("example_vignette", {
    sink->add(pathlet::PassTypeBuilder("vignette", "darkens the image towards the corners (out-of-tree example)")
                  .param_float("strength", 0.6, 0.0, 1.0, "how dark the corners get")
                  .param_float("radius", 0.75, 0.1, 2.0, "distance from the centre where darkening starts")
                  .input_texture("src", "any", "image")
                  .output_texture("dst", "rgba8", "image with vignette")
                  .make<Vignette>());
})
