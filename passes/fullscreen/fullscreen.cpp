// fullscreen: runs a fragment shader named by a parameter over the whole output, with up to
// four optional input textures. A quick way to try an image-space idea without C++.
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <string>

namespace {

class Fullscreen : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        prog_ = &ctx.program({"fullscreen.vert", ctx.params().s("shader")});
    }
    void execute(pathlet::PassContext& ctx) override {
        ctx.bind_framebuffer({"color"});
        prog_->use();
        // The user's shader declares whichever of these it needs (the samplers u_input0..3, u_param
        // and u_strength come from the declaration).
        const pathlet::ShaderProgram& p = *prog_;
        if (p.declares("u_time")) p.set("u_time", float(ctx.time()));
        if (p.declares("u_frame")) p.set("u_frame", int(ctx.frame_index()));
        if (p.declares("u_size")) p.set("u_size", ctx.output_size());
        ctx.draw_fullscreen();
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
};

pathlet::PassTypeInfo fullscreen_type() {
    auto b = pathlet::PassTypeBuilder(
        "fullscreen",
        "runs a fragment shader file over the output: samplers u_input0..u_input3, uniforms u_time u_frame u_size "
        "u_param u_strength");
    b.param_string("shader", "gradient.frag", "fragment shader file, looked up on the shader path")
        .param_vec3("param", {1, 1, 1}, "free vector handed to the shader as u_param")
        .param_float("strength", 1.0, -100.0, 100.0, "free scalar handed to the shader as u_strength");
    for (int i = 0; i < 4; ++i)
        b.input_texture("input" + std::to_string(i), "any", "optional input, sampler u_input" + std::to_string(i),
                        {.optional = true});
    return b.output_texture("color", "rgba8", "the shader's output").make<Fullscreen>();
}

}  // namespace

PATHLET_PLUGIN("fullscreen", { sink->add(fullscreen_type()); })
