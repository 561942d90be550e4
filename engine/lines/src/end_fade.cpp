// The line kit's end fade: parameters declared once, uniforms for engine/lines/shaders/line_fade.glsl.
#include <pathlet/lines.hpp>

#include <algorithm>
#include <cmath>

namespace pathlet::lines {

namespace {
const std::vector<std::string> kMeasures{"time", "arc_length"};
const std::vector<std::string> kCurves{"linear", "smooth", "round"};

int index_of(const std::vector<std::string>& v, const std::string& s) {
    return int(std::find(v.begin(), v.end(), s) - v.begin());
}

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
        .param_enum("fade_measure", "time", kMeasures,
                    "time: fade over a share of the window, as in the study (fast pathlets get long fades, slow "
                    "ones short); arc_length: over a fixed length along the line (share x median speed x window), "
                    "the same on screen for every pathlet")
        .param_enum("fade_curve", "linear", kCurves,
                    "profile along the fade: linear, smooth (Hermite), round (sqrt: fuller ends)")
        .param_float("fade_floor", 0.0, 0.0, 1.0, "value left at the very end (0 = nothing)");
}

void EndFade::setup(PassContext& ctx) {
    const Scene& s = ctx.scene().cpu();
    reference_ = typical_pathlet_length(s, s.lines.timeless ? 0.0f : ctx.params().f("window"));  // streamlines: whole
}

void EndFade::set_uniforms(PassContext& ctx, const ShaderProgram& prog) const {
    const Params& p = ctx.params();
    const int measure = index_of(kMeasures, p.s("fade_measure"));
    const float unit = measure == 0 ? 1.0f : reference_;  // age is already a share of the window
    prog.set("u_fade", glm::vec2(p.f("tail_fade"), p.f("head_fade")) * unit);
    prog.set("u_fade_measure", measure);
    prog.set("u_fade_curve", index_of(kCurves, p.s("fade_curve")));
    prog.set("u_fade_floor", p.f("fade_floor"));
}

}  // namespace pathlet::lines
