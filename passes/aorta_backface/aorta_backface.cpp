// aorta_backface: the vessel wall as context behind the lines (the study's figures). It draws
// after the lighting, over the finished image, depth-tested against the G-buffer depth, so the
// wall shows only where no line is in front and never enters LineAO (no darkened lines, the
// study's Fig. 11c). With show = false, or a scene without a wall, the image passes through
// bit for bit.
#include <pathlet/gpu_scene.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <algorithm>
#include <vector>

namespace {
enum class Mode { backfaces, whole };  // the choices of `mode`

class AortaBackface : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        clear_shows_wall_ = ctx.params().b("clear_shows_wall");
        prog_ = &ctx.program({"aorta_backface.vert", "aorta_backface.frag"},
                             clear_shows_wall_ ? std::vector<std::string>{"CLEAR_SHOWS_WALL"} : std::vector<std::string>{});
        const pathlet::Scene& scene = ctx.scene().cpu();
        const float simplify = ctx.params().f("simplify");
        if (scene.mesh && !scene.mesh->empty() && (simplify != simplified_at_ || !wall_.vao())) {
            // Vertex clustering: the wall is quiet context, and on llvmpipe its vertex work is
            // the pass's cost (97k triangles of the phantom: 13-16 ms at 720p, lines or not).
            const pathlet::Bounds b = scene.mesh->bounds();
            const pathlet::Mesh m = scene.mesh->simplified(simplify * glm::length(b.hi - b.lo));
            wall_.upload(m);
            normal_sign_ = outward_sign(m, ccw_outward_);
            simplified_at_ = simplify;
        }
    }


    void execute(pathlet::PassContext& ctx) override {
        const pathlet::Params& p = ctx.params();
        pathlet::Texture src = ctx.texture("color"), dst = ctx.texture("final");
        glCopyImageSubData(src.id, GL_TEXTURE_2D, 0, 0, 0, 0, dst.id, GL_TEXTURE_2D, 0, 0, 0, 0, dst.width, dst.height, 1);
        const pathlet::GpuScene& scene = ctx.scene();
        if (!p.b("show") || !scene.has_mesh()) return;
        if (clear_shows_wall_) {
            ctx.bind_framebuffer({"final"}, "");  // the shader reads the depth: not attached
        } else {
            ctx.bind_framebuffer({"final"}, "depth");
            glEnable(GL_DEPTH_TEST);
            glDepthMask(GL_FALSE);  // the G-buffer depth stays as it is
        }
        // Back faces only: let the rasteriser cull the near side (half the wall's pixels and
        // setup) when the winding is consistent; the shader's normal test stays as a fallback.
        if (p.e<Mode>("mode") == Mode::backfaces) {
            glEnable(GL_CULL_FACE);
            glFrontFace(GL_CCW);
            glCullFace(ccw_outward_ ? GL_FRONT : GL_BACK);
        }
        glEnable(GL_BLEND);
        // Colour: opacity over what is there; alpha: 1 where the wall is (the background's alpha
        // is 0, and an image viewer would show a transparent wall).
        glBlendColor(0.0f, 0.0f, 0.0f, p.f("opacity"));
        glBlendFuncSeparate(GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA, GL_ONE, GL_ZERO);
        prog_->use();
        prog_->set("u_view", ctx.camera().view);
        prog_->set("u_proj", ctx.camera().proj);
        prog_->set("u_normal_sign", normal_sign_);
        glBindVertexArray(wall_.vao());
        glDrawElements(GL_TRIANGLES, wall_.index_count(), GL_UNSIGNED_INT, nullptr);
        ctx.stat("wall triangles", double(wall_.index_count() / 3));
    }

private:
    // +1 when the mesh's normals point out of the vessel, -1 when in (marching cubes and
    // exporters differ): the winding's signed volume says which way is out, and the normals
    // either agree with the winding or not.
    static float outward_sign(const pathlet::Mesh& m, bool& ccw_outward) {
        ccw_outward = true;
        if (m.empty() || m.normal.size() != m.position.size()) return 1.0f;
        double volume = 0.0, agree = 0.0;
        for (size_t t = 0; t + 2 < m.index.size(); t += 3) {
            const glm::dvec3 a = m.position[m.index[t]], b = m.position[m.index[t + 1]], c = m.position[m.index[t + 2]];
            const glm::dvec3 face = glm::cross(b - a, c - a);
            volume += glm::dot(a, glm::cross(b, c));
            agree += glm::dot(face, glm::dvec3(m.normal[m.index[t]] + m.normal[m.index[t + 1]] + m.normal[m.index[t + 2]]));
        }
        ccw_outward = volume > 0.0;  // counter-clockwise seen from outside: a positive volume
        return (volume > 0.0) == (agree > 0.0) ? 1.0f : -1.0f;
    }

    pathlet::ShaderProgram* prog_ = nullptr;
    pathlet::GpuMesh wall_;  // the drawn (simplified) wall
    float simplified_at_ = -1.0f;
    float normal_sign_ = 1.0f;
    bool ccw_outward_ = true;
    bool clear_shows_wall_ = false;
};

}  // namespace

PATHLET_PLUGIN("aorta_backface", {
    sink->add(pathlet::PassTypeBuilder("aorta_backface",
                                       "the vessel wall as quiet, lit context behind the lines, over the finished image "
                                       "(never in LineAO)")
                  .param_bool("show", true, "draw the wall (false: the image passes through unchanged)")
                  .param_enum("mode", "backfaces", {"backfaces", "whole"},
                              "backfaces: the far side of the vessel, seen through it (the study); whole: every face")
                  .param_color("wall_color", {0.55f, 0.62f, 0.72f}, "wall colour before shading")
                  .param_float("opacity", 0.3, 0.0, 1.0, "how strongly the wall covers the background")
                  .param_bool("clear_shows_wall", false,
                              "also draw the wall where the depth has a line but the image is clear (alpha 0): for OIT "
                              "graphs, whose G-buffer depth also holds fragments too faint to show (their rims and "
                              "faded tips)")
                  .param_float("simplify", 0.008, 0.0, 0.05,
                               "cell of the wall's vertex clustering as a fraction of its bounding-box diagonal "
                               "(0.008: 1.8 mm on the phantom, 97k -> 19k triangles, 11 -> 4 ms at 720p); 0 = the full mesh")
                  .input_texture("color", "rgba8", "the finished image (e.g. bilateral's final)")
                  .input_texture("depth", "depth24", "the G-buffer depth: lines in front hide the wall")
                  .output_texture("final", "rgba8", "the image with the wall behind the lines")
                  .make<AortaBackface>());
})
