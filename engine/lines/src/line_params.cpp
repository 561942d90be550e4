// The line kit's declarations: shared line parameters and LineAO's G-buffer outputs, once.
#include <pathlet/lines.hpp>

#include <algorithm>

namespace pathlet::lines {

const std::vector<std::string>& colormaps() {
    static const std::vector<std::string> names{"green_red", "viridis", "coolwarm", "grey", "direction"};
    return names;
}

PassTypeBuilder& declare_window_param(PassTypeBuilder& b) {
    return b.param_float("window", 1.0, -1.0, 1e6,
                         "pathlet length in seconds: the parts of the lines with times in [t - window, t] are drawn, "
                         "clipped smoothly inside a segment; <= 0 draws every line whole");
}

PassTypeBuilder& declare_line_width_params(PassTypeBuilder& b) {
    return b
        .param_float("line_width", 0.0, 0.0, 1e4,
                     "quad width in world units, halo included; 0 = auto: 0.5 % of the data's bounding-box "
                     "diagonal (~3.5 px at 720p when the data fills the frame; 1.1 mm on the phantom)")
        .param_float("width_factor", 1.0, 0.01, 100.0,
                     "the auto width (line_width 0) times this: how a graph widens or thins its lines relative to the "
                     "data (variant 3 tapers its ends, so it draws them wider); an explicit line_width is used as given");
}

TimeWindow time_window(const GpuScene& scene, float window, double t) {
    if (!(window > 0.0f) || scene.cpu().lines.timeless) return {};
    return {t - double(window), t, true};
}

float line_width(const PassContext& ctx) {
    return ctx.scene().line_width(ctx.params().f("line_width"), ctx.params().f("width_factor"));
}

PassTypeBuilder& declare_params(PassTypeBuilder& b, const Hooks& defaults) {
    return declare_line_width_params(declare_window_param(b))
        .param_float("halo", 0.2, 0.0, 0.9,
                     "fraction of the width drawn as halo, split between both rims (study: 20 %); 0 = off")
        .param_float("halo_min_px", 0.0, 0.0, 16.0,
                     "the halo band is at least this many pixels wide on screen (at most half the half width): "
                     "a bolder outline than the line's own at small sizes; 0 = the fraction alone, as a "
                     "supersampled render draws it (the band's tint is averaged over each pixel's footprint, so "
                     "even a band far thinner than a pixel reads as an even, faint outline)",
                     {.pixels = true})
        .param_color("halo_color", {0.0f, 0.0f, 0.0f},
                     "colour the halo gradient runs to at the rim (dark edges read as tube outlines)")
        .param_float("halo_depth", 0.01, 0.0, 1.0,
                     "how far the halo is pushed back at the rim, in normalised linear depth: neighbours closer "
                     "than this merge, farther lines get a gap")
        .param_enum("colormap", "green_red", colormaps(),
                    "speed colour map: green_red (study: green slow, yellow, red fast), viridis, coolwarm, grey; or "
                    "direction: RGB = |dx|, |dy|, |dz| of the line's unit tangent (the tractography convention)")
        .param_float("speed_min", 0.0, -1.0, 1e9, "speed mapped to the colour map's start; <= 0: the data's 1st percentile",
                     {.at_most = "speed_max", .automatic_at_or_below = 0.0})
        .param_float("speed_max", 0.0, -1.0, 1e9, "speed mapped to the colour map's end; <= 0: the data's 99th percentile")
        .param_color("background", {1.0f, 1.0f, 1.0f}, "colour of pixels without lines")
        .param_float("lod", 0.1, 0.0, 16.0,
                     "level of detail: points a Douglas-Peucker simplification of the line drops within this many "
                     "pixels (at the line's nearest distance) are not drawn; 0 = every point, exact",
                     {.pixels = true})
        .param_bool("cull", true,
                    "draw only the line chunks that can be seen, culled on the GPU: frustum culling and two-phase "
                    "occlusion culling against this pass's depth (the picture stays the same); false: every chunk of "
                    "the window")
        .param_int("cull_min_segments", 70000, 0, 1 << 30,
                   "cull only when the window holds at least this many data segments: below it the culling's "
                   "fixed work (its dispatches and the depth pyramid) costs more than the hidden chunks save "
                   "(llvmpipe, study phantom, 720p: even at 68k, 15 % faster at 78k); 0 = always")
        .param_hook(HookRole::color, defaults.color,
                    "colour hook: a GLSL file (on the shader path or next to the graph) defining vec4 "
                    "line_color_hook(vec4 rgba, LinePoint p); empty = the colour map as it is, opaque")
        .param_hook(HookRole::width, defaults.width,
                    "width hook: a GLSL file defining float line_width_hook(LinePoint p), a multiplier of the "
                    "width (0..4); empty = full width")
        .input_buffer("hook_buffer",
                      "data the hooks read beside LinePoint (line_hook_buffer.glsl: a uint array on the pin's binding), "
                      "e.g. opacity_blend's per-segment opacity for optimized_fade.glsl",
                      {.optional = true});
}

PassTypeBuilder& declare_gbuffer_outputs(PassTypeBuilder& b, bool optional) {
    const PinOptions core{.optional = optional};
    return b.output_texture("color", "rgba8", "line colour incl. halos; background: `background` with alpha 0", core)
        .output_texture("normal_depth", "rgba16f",
                        "xyz: view-space unit tube normal; w: linear depth (-z_eye - near) / (far - near); "
                        "background: (0, 0, 0, 1)",
                        core)
        .output_texture("zoom", "r32f", "pixels per world unit at the fragment, (H/2) P[1][1] / -z_eye; background 0",
                        core)
        .output_texture("depth", "depth24", "z-buffer of the tube surfaces (halos pushed back)", core)
        .output_texture("line_id", "r32i", "line index per pixel, -1 on background (bind it to get it)",
                        {.optional = true})
        .output_texture("edge", "rgba8",
                        "the nearer rim per pixel for edge_aa: rg = 0.5 + 0.5 * outward screen direction, b = distance "
                        "in pixels / 2 (clamped to 1), a = 0.2 + 0.2 * line width in px (clamped to 1), 0 on background (bind it "
                        "to get it)",
                        {.optional = true})
        .output_texture("tangent", "rgba16f",
                        "xyz: view-space unit tangent of the front line, w: eye depth from the pixel's point (normal_depth's "
                        "w) back to the quad through the line's axis, world units; 0 on background: with normal_depth "
                        "they give the tube's axis (volume_ao; bind it to get it)",
                        {.optional = true});
}

PassTypeBuilder gbuffer_pass_type(const std::string& type, const std::string& doc, const Hooks& defaults) {
    PassTypeBuilder b(type, doc);
    declare_params(b, defaults);
    declare_gbuffer_outputs(b);
    return b;
}

}  // namespace pathlet::lines
