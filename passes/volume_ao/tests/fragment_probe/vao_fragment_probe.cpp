// Test fixture: per-fragment volume AO from a line pass's own fragment stage (the line kit's
// line_volume_ao_fragment), depth-tested like a G-buffer, into `ao` (1 on background).
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

namespace {

namespace lines = pathlet::lines;

class FragmentProbe : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        prog_ = &lines::program(ctx, {"vao_fragment_probe.frag"}, lines::hooks(ctx), lines::VolumeAo::defines(ctx));
    }
    void execute(pathlet::PassContext& ctx) override {
        ctx.bind_framebuffer({"ao"}, "depth");
        lines::clear_color(0, glm::vec4(1.0f));
        lines::clear_depth(1.0f);
        prog_->use();
        vao_.bind(ctx, *prog_);
        drawer_.draw(ctx, *prog_);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    lines::Drawer drawer_;
    lines::VolumeAo vao_;
};

}  // namespace

PATHLET_PLUGIN("vao_fragment_probe", {
    pathlet::PassTypeBuilder b("vao_fragment_probe", "test fixture: every fragment's own volume AO, depth-tested");
    pathlet::lines::declare_params(b);
    pathlet::lines::declare_volume_ao_params(b)
        .input_buffer("density", "the line-density volume")
        .output_texture("ao", "r16f", "the nearest fragment's AO, 1 on background")
        .output_texture("depth", "depth24", "depth test");
    sink->add(b.make<FragmentProbe>());
})
