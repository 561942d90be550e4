// The line kit's end fade: parameters declared once, uniforms for engine/lines/shaders/line_fade.glsl.
#include <pathlet/lines.hpp>

#include <algorithm>
#include <cmath>

namespace pathlet::lines {

namespace {
enum class Measure { time, arc_length };  // the order of the choices below

// Median speed x window, or with whole lines the median line length.
float typical_pathlet_length(const Scene& s, float window) {
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
}  // namespace

PassTypeBuilder& declare_fade_params(PassTypeBuilder& b, double tail_fade, double head_fade,
                                     const std::string& what_fades) {
    return b
        .param_float("tail_fade", tail_fade, 0.0, 1.0,
                     "length of the " + what_fades + " fade at the tail (the oldest end), as a share of the pathlet: "
                     "of the window (fade_measure=time) or of a typical pathlet's length (arc_length); 0 = none")
        .param_float("head_fade", head_fade, 0.0, 1.0,
                     "length of the " + what_fades + " fade at the head (the newest end), the same way; 0 = none")
        .param_enum("fade_measure", "time", {"time", "arc_length"},
                    "time: fade over a share of the window, as in the study (fast pathlets get long fades, slow "
                    "ones short); arc_length: over a fixed length along the line (share x median speed x window), "
                    "the same on screen for every pathlet")
        .param_enum("fade_curve", "linear", {"linear", "smooth", "round"},
                    "profile along the fade: linear, smooth (Hermite), round (sqrt: fuller ends)")
        .param_float("fade_floor", 0.0, 0.0, 1.0, "value left at the very end (0 = nothing)");
}

void EndFade::setup(PassContext& ctx) { reference_ = typical_pathlet_length(ctx.scene().cpu(), ctx.params().f("window")); }

// fade_measure, fade_curve and fade_floor reach line_fade.glsl by declaration (u_<name>); the
// lengths are derived: in arc-length mode a share of the typical pathlet.
void EndFade::set_uniforms(PassContext& ctx, const ShaderProgram& prog) const {
    const Params& p = ctx.params();
    const float unit = p.e<Measure>("fade_measure") == Measure::time ? 1.0f : reference_;  // age: a share already
    prog.set("u_fade", glm::vec2(p.f("tail_fade"), p.f("head_fade")) * unit);
}

}  // namespace pathlet::lines
