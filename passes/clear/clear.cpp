// clear: fills its output with a constant colour. The smallest useful pass.
#include <pathlet/plugin.hpp>

namespace {

class Clear : public pathlet::Pass {
public:
    void execute(pathlet::PassContext& ctx) override {
        glm::vec3 c = ctx.params().v3("color");
        float a = ctx.params().f("alpha");
        const float rgba[4] = {c.r, c.g, c.b, a};
        glClearTexImage(ctx.texture("color").id, 0, GL_RGBA, GL_FLOAT, rgba);
    }
};

pathlet::PassTypeInfo clear_type() {
    return pathlet::PassTypeBuilder("clear", "fills a texture with one colour")
        .param_color("color", {1, 1, 1}, "the colour (RGB in 0..1, or \"#rrggbb\")")
        .param_float("alpha", 1.0, 0.0, 1.0, "alpha written with the colour")
        .output_texture("color", "rgba8", "the cleared texture")
        .make<Clear>();
}

}  // namespace

PATHLET_PLUGIN("clear", { sink->add(clear_type()); })
