// isl: illuminated streamlines (Zoeckler et al. 1996) on the same pathlet quads, colours,
// time window and halos as the gbuffer pass: a local-lighting image to compare LineAO with.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <glm/glm.hpp>

namespace {

namespace lines = pathlet::lines;

class Isl : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        edge_ = ctx.connected("edge");  // optional: the rims for edge_aa
        std::vector<std::string> defines;
        if (edge_) defines.push_back("WRITE_EDGE");
        // Whole exponents are compiled in (setup runs again when a parameter changes).
        for (const auto& d : pathlet::whole_exponent("ISL_SPECULAR_EXPONENT", ctx.params().f("exponent")))
            defines.push_back(d);
        for (const auto& d : pathlet::whole_exponent("ISL_DIFFUSE_EXPONENT", ctx.params().f("diffuse_exponent")))
            defines.push_back(d);
        prog_ = &lines::program(ctx, {"isl.frag"}, lines::hooks(ctx), defines);
    }

    void execute(pathlet::PassContext& ctx) override {
        const pathlet::Params& p = ctx.params();
        ctx.bind_framebuffer(edge_ ? std::vector<std::string>{"color", "edge"} : std::vector<std::string>{"color"},
                             "depth");
        lines::clear_color(0, glm::vec4(p.v3("background"), 1.0f));  // a final image: opaque everywhere
        if (edge_) lines::clear_color(1, glm::vec4(0.5f, 0.5f, 1.0f, 0.0f));  // alpha 0: no line
        lines::clear_depth(1.0f);

        prog_->use();
        glm::vec3 dir = p.v3("light_dir");
        glm::vec3 to_light = glm::length(dir) > 1e-12f ? -glm::normalize(dir) : glm::vec3(0, 0, 1);
        prog_->set("u_light", to_light);  // the other factors by declaration
        drawer_.draw(ctx, *prog_);
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    lines::Drawer drawer_;
    bool edge_ = false;
};

pathlet::PassTypeInfo isl_type() {
    pathlet::PassTypeBuilder b("isl",
                               "illuminated streamlines (Zoeckler et al.): pathlet quads lit from their tangent, "
                               "with the gbuffer pass's colours, time window and halos");
    lines::declare_params(b)
        .param_vec3("light_dir", {1.0f, -1.0f, -1.0f},
                    "direction the light travels, view space (default: from the upper left, in front, into the scene)")
        .param_float("ambient", 0.2, 0.0, 1.0, "ambient factor on the line colour")
        .param_float("diffuse", 0.8, 0.0, 2.0, "diffuse factor: sqrt(1 - (L.T)^2)^p times the line colour")
        .param_float("specular", 0.5, 0.0, 2.0, "white specular factor: max(0, sqrt(1-(L.T)^2) sqrt(1-(V.T)^2) - (L.T)(V.T))^n")
        .param_float("exponent", 50.0, 1.0, 1000.0, "specular exponent n")
        .param_float("diffuse_exponent", 1.0, 0.1, 10.0,
                     "diffuse exponent p (1: Zoeckler's term; larger p darkens lines along the light, cf. Mallo et al.)")
        .output_texture("color", "rgba8", "the lit image; background colour where there are no lines")
        .output_texture("depth", "depth24", "z-buffer of the tube surfaces (halos pushed back)")
        .output_texture("edge", "rgba8", "the nearer rim per pixel for edge_aa, as the gbuffer's (bind it to get it)", {.optional = true});
    return b.make<Isl>();
}

}  // namespace

PATHLET_PLUGIN("isl", { sink->add(isl_type()); })
