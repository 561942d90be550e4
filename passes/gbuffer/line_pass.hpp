// Shared by the gbuffer and isl passes (isl includes it from here): the parameters of pathlet
// quads, declared once for both types, and the per-frame uniforms and draw that feed
// shaders/line_quad.geom and shaders/line_common.glsl.
#pragma once

#include <pathlet/gpu_scene.hpp>
#include <pathlet/pass.hpp>
#include <pathlet/shader.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace pathlet::line_pass {

// Order matches the COLORMAP_* constants in shaders/colormap.glsl.
inline const std::vector<std::string>& colormaps() {
    static const std::vector<std::string> names{"green_red", "viridis", "coolwarm", "grey"};
    return names;
}

inline PassTypeBuilder& declare_params(PassTypeBuilder& b) {
    return b
        .param_float("window", 1.0, -1.0, 1e6,
                     "pathlet length in seconds: the parts of the lines with times in [t - window, t] are drawn, "
                     "clipped smoothly inside a segment; <= 0 draws every line whole")
        .param_float("line_width", 0.0, 0.0, 1e4,
                     "quad width in world units, halo included; 0 = auto: 0.35 % of the data's bounding-box "
                     "diagonal (~2 px at 720p when the data fills the frame; 0.77 mm on the phantom)")
        .param_float("halo", 0.2, 0.0, 0.9,
                     "fraction of the width drawn as halo, split between both rims (study: 20 %); 0 = off")
        .param_color("halo_color", {0.0f, 0.0f, 0.0f},
                     "colour the halo gradient runs to at the rim (dark edges read as tube outlines)")
        .param_float("halo_depth", 0.01, 0.0, 1.0,
                     "how far the halo is pushed back at the rim, in normalised linear depth: neighbours closer "
                     "than this merge, farther lines get a gap")
        .param_enum("colormap", "green_red", colormaps(),
                    "speed colour map: green_red (study: green slow, yellow, red fast), viridis, coolwarm, grey")
        .param_float("speed_min", 0.0, -1.0, 1e9, "speed mapped to the colour map's start; <= 0: the data's 1st percentile")
        .param_float("speed_max", 0.0, -1.0, 1e9, "speed mapped to the colour map's end; <= 0: the data's 99th percentile")
        .param_color("background", {1.0f, 1.0f, 1.0f}, "colour of pixels without lines");
}

inline int colormap_index(const std::string& name) {
    const auto& n = colormaps();
    return int(std::find(n.begin(), n.end(), name) - n.begin()) % int(n.size());
}

// Sets line_common.glsl's uniforms on `prog` (already in use), draws the pathlets of the
// current time window into the bound framebuffer with depth testing, reports the counts.
inline void draw(PassContext& ctx, const ShaderProgram& prog, GpuScene::Ranges& ranges) {
    const Params& p = ctx.params();
    const Camera& cam = ctx.camera();
    const GpuScene& scene = ctx.scene();
    const float window = p.f("window");
    const bool windowed = window > 0.0f;
    const double t = ctx.time();
    // CPU sub-ranges per line: far cheaper on llvmpipe than culling in the GS or the FS.
    scene.ranges(windowed ? t - window : 0.0, windowed ? t : 0.0, ranges);

    float smin = p.f("speed_min") > 0.0f ? p.f("speed_min") : scene.speed_min();
    float smax = p.f("speed_max") > 0.0f ? p.f("speed_max") : scene.speed_max();
    if (!(smax > smin)) smax = smin + 1.0f;
    prog.set("u_view", cam.view);
    prog.set("u_proj", cam.proj);
    prog.set("u_window", glm::vec2(float(t) - window, float(t)));
    prog.set("u_windowed", windowed ? 1 : 0);
    prog.set("u_half_width", 0.5f * scene.line_width(p.f("line_width")));
    prog.set("u_halo", p.f("halo"));
    prog.set("u_halo_depth", p.f("halo_depth"));
    prog.set("u_halo_color", p.v3("halo_color"));
    prog.set("u_depth_range", glm::vec2(cam.near_plane, cam.far_plane));
    prog.set("u_speed_range", glm::vec2(smin, smax));
    prog.set("u_colormap", colormap_index(p.s("colormap")));

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);  // halos pushed past the far plane still land on the cleared 1.0
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);  // quads face either way
    scene.draw_lines(ranges);
    glDisable(GL_DEPTH_TEST);

    ctx.stat("segments", double(ranges.segments));
    ctx.stat("lines", double(ranges.first.size()));
}

// Clear values go through the bound framebuffer, one attachment at a time.
inline GLuint bound_framebuffer() {
    GLint fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    return GLuint(fbo);
}

inline void prepare_clear() {
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
}

}  // namespace pathlet::line_pass
