// A test fixture for the line kit's hooks: a G-buffer line pass whose colour hook writes what
// it sees (age; arc lengths) into the colour and whose width hook can taper by age. `typo`
// sets a uniform the program does not declare, which must fail loudly.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

#include <algorithm>

namespace {

const std::vector<std::string> kProbes{"age", "arc", "taper", "typo", "widen"};

class KitProbe : public pathlet::lines::GBufferPass {
protected:
    void set_uniforms(pathlet::PassContext& ctx, const pathlet::ShaderProgram& prog) override {
        const std::string probe = ctx.params().s("probe");
        int mode = int(std::find(kProbes.begin(), kProbes.end(), probe) - kProbes.begin());
        prog.set("u_mode", mode);
        prog.set(probe == "typo" ? "u_sclae" : "u_scale", ctx.params().f("scale"));
    }
};

}  // namespace

PATHLET_PLUGIN("kit_probe", {
    sink->add(pathlet::lines::gbuffer_pass_type("kit_probe", "test fixture: writes what the kit's hooks see",
                                                {.width = "kit_probe_width.geom", .color = "kit_probe_color.frag"})
                  .param_enum("probe", "age", kProbes, "age: R = age; arc: R, G = arc from head, tail / scale; "
                                                       "taper: width 1 - age; typo: sets a misspelt uniform; widen: width x scale")
                  .param_float("scale", 1.0, 1e-6, 1e9, "arc length that maps to colour 1")
                  .make<KitProbe>());
})
