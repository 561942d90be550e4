// blur: separable Gaussian blur, horizontal into `tmp`, vertical into `dst`.
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

namespace {

class Blur : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override { prog_ = &ctx.program({"fullscreen.vert", "blur.frag"}); }
    // u_radius, u_sigma and u_src come from the declaration; the pass only turns the filter.
    void execute(pathlet::PassContext& ctx) override {
        prog_->use();
        ctx.bind_framebuffer({"tmp"});  // horizontal: src -> tmp
        prog_->set("u_dir", glm::vec2(1, 0));
        ctx.draw_fullscreen();
        ctx.bind_framebuffer({"dst"});  // vertical: tmp -> dst
        prog_->bind_texture("u_src", ctx.texture("tmp").id);
        prog_->set("u_dir", glm::vec2(0, 1));
        ctx.draw_fullscreen();
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
};

pathlet::PassTypeInfo blur_type() {
    return pathlet::PassTypeBuilder("blur", "separable Gaussian blur of a colour texture")
        .param_int("radius", 4, 0, 64, "kernel half-width in pixels")
        .param_float("sigma", 2.0, 0.1, 64.0, "Gaussian standard deviation in pixels")
        .input_texture("src", "any", "image to blur")
        .output_texture("dst", "rgba8", "blurred image")
        .internal_texture("tmp", "rgba16f", "horizontal pass result")
        .make<Blur>();
}

}  // namespace

PATHLET_PLUGIN("blur", { sink->add(blur_type()); })
