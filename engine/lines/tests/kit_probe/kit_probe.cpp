// A test fixture for the line kit's hooks: a G-buffer line pass whose colour hook writes what
// it sees (age; arc lengths) into the colour and whose width hook can taper by age. `typo`
// sets a uniform the program does not declare, which must fail loudly. `bound` colours the
// lines from the pass's own storage buffer and texture, at the binding point and unit the kit's
// culling also uses: what the pass bound must be there when the kit draws.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

#include <algorithm>

namespace {

const std::vector<std::string> kProbes{"age", "arc", "taper", "typo", "widen", "bound"};
constexpr GLuint kProbeBinding = 0;  // PROBE_BUFFER_BINDING: the kit's culling binds point 0 too
// What `bound` adds up to: (0.25, 0.5, 0) on every line pixel.
constexpr float kProbeBuffer[4] = {0.25f, 0.0f, 0.0f, 1.0f};
constexpr uint8_t kProbeTexel[4] = {0, 128, 0, 255};

class KitProbe : public pathlet::lines::GBufferPass {
public:
    ~KitProbe() override {
        if (buffer_) glDeleteBuffers(1, &buffer_);
        if (texture_) glDeleteTextures(1, &texture_);
    }
    void setup(pathlet::PassContext& ctx) override {
        targets_ = pathlet::lines::gbuffer_targets(ctx);
        std::vector<std::string> defines = targets_.defines;
        defines.push_back("PROBE_BUFFER_BINDING " + std::to_string(kProbeBinding));
        prog_ = &pathlet::lines::program(ctx, {"line_gbuffer.frag"}, pathlet::lines::hooks(ctx), defines);
        if (!buffer_) {
            glCreateBuffers(1, &buffer_);
            glNamedBufferStorage(buffer_, sizeof kProbeBuffer, kProbeBuffer, 0);
            glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
            glTextureStorage2D(texture_, 1, GL_RGBA8, 1, 1);
            glTextureSubImage2D(texture_, 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, kProbeTexel);
        }
    }

protected:
    void set_uniforms(pathlet::PassContext& ctx, const pathlet::ShaderProgram& prog) override {
        const std::string probe = ctx.params().s("probe");
        int mode = int(std::find(kProbes.begin(), kProbes.end(), probe) - kProbes.begin());
        prog.set("u_mode", mode);
        prog.set(probe == "typo" ? "u_sclae" : "u_scale", ctx.params().f("scale"));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kProbeBinding, buffer_);
        prog.bind_texture("u_probe_texture", texture_);
    }

private:
    GLuint buffer_ = 0, texture_ = 0;
};

}  // namespace

PATHLET_PLUGIN("kit_probe", {
    sink->add(pathlet::lines::gbuffer_pass_type("kit_probe", "test fixture: writes what the kit's hooks see",
                                                {.width = "kit_probe_width.geom", .color = "kit_probe_color.frag"})
                  .param_enum("probe", "age", kProbes, "age: R = age; arc: R, G = arc from head, tail / scale; "
                                                       "taper: width 1 - age; typo: sets a misspelt uniform; widen: width x scale; "
                                                       "bound: colour from the pass's own buffer and texture")
                  .param_float("scale", 1.0, 1e-6, 1e9, "arc length that maps to colour 1")
                  .make<KitProbe>());
})
