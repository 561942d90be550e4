// geometric_fade: variant 3 of the study (seed §IV.d). Pathlet ends taper in width instead of
// opacity, so the G-buffer stays opaque and LineAO needs no transparency. It is the line kit's
// G-buffer pass with a width hook (taper_width.geom); its outputs are gbuffer's.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

namespace lines = pathlet::lines;

const std::vector<std::string> kMeasures{"time", "arc_length"};
const std::vector<std::string> kCurves{"linear", "smooth", "round"};

int index_of(const std::vector<std::string>& v, const std::string& s) {
    return int(std::find(v.begin(), v.end(), s) - v.begin());
}

// A typical pathlet's length (world units): median speed x window, or with whole lines the
// median line length. Arc-length tapers are fractions of it, so the same tail_fade reads the
// same in both modes, but every pathlet gets the same taper on screen.
float typical_length(const pathlet::Scene& s, float window) {
    const auto& pl = s.lines;
    std::vector<float> v;
    if (window > 0.0f) {
        for (const auto& u : pl.velocity)
            if (float sp = glm::length(u); std::isfinite(sp)) v.push_back(sp);
    } else {
        for (const auto& r : pl.lines) {
            double len = 0;
            for (uint32_t k = 1; k < r.count; ++k)
                if (float d = glm::length(pl.position[r.first + k] - pl.position[r.first + k - 1]); std::isfinite(d))
                    len += d;
            v.push_back(float(len));
        }
    }
    if (v.empty()) return 1.0f;
    std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
    float m = v[v.size() / 2] * (window > 0.0f ? window : 1.0f);
    return m > 0.0f ? m : 1.0f;
}

class GeometricFade : public lines::GBufferPass {
public:
    GeometricFade() : GBufferPass({.width = "taper_width.geom"}) {}

    void setup(pathlet::PassContext& ctx) override {
        GBufferPass::setup(ctx);
        reference_ = typical_length(ctx.scene().cpu(), ctx.params().f("window"));
    }

protected:
    void set_uniforms(pathlet::PassContext& ctx, const pathlet::ShaderProgram& prog) override {
        const pathlet::Params& p = ctx.params();
        const int measure = index_of(kMeasures, p.s("fade_measure"));
        const float unit = measure == 0 ? 1.0f : reference_;  // age is already a fraction of the window
        prog.set("u_fade", glm::vec2(p.f("tail_fade"), p.f("head_fade")) * unit);
        prog.set("u_measure", measure);
        prog.set("u_curve", index_of(kCurves, p.s("curve")));
        prog.set("u_min_width", p.f("min_width"));
    }

private:
    float reference_ = 1.0f;
};

}  // namespace

PATHLET_PLUGIN("geometric_fade", {
    sink->add(lines::gbuffer_pass_type(
                  "geometric_fade",
                  "variant 3 of the study: pathlet ends taper in width instead of opacity; writes LineAO's "
                  "G-buffer like gbuffer, with tube normals and depth of the tapered width")
                  .param_float("tail_fade", 0.5, 0.0, 1.0,
                               "taper at the tail (the oldest end), as a fraction of the pathlet: of the window "
                               "(fade_measure=time) or of a typical pathlet's length (arc_length); 0 = none")
                  .param_float("head_fade", 0.15, 0.0, 1.0, "taper at the head (the newest end), the same way; 0 = none")
                  .param_enum("fade_measure", "time", kMeasures,
                              "time: taper over a share of the window, as in the study (fast pathlets get long "
                              "tapers, slow ones short); arc_length: over a fixed length along the line "
                              "(tail_fade x median speed x window), the same on screen for every pathlet")
                  .param_enum("curve", "linear", kCurves,
                              "width profile along the taper: linear, smooth (Hermite), round (sqrt: fuller tips)")
                  .param_float("min_width", 0.0, 0.0, 1.0, "width left at the very end, as a fraction of the full width")
                  .make<GeometricFade>());
})
