#pragma once
// `pathlet quality` as a function (also the Python module's pathlet.quality): the graph run
// with extra bindings added in memory (the G-buffer's line_id and the AO that reaches the
// image: bilateral's ao_smooth, lineao's or volume_ao's ao, or resolve_list's front fragment
// under OIT with per-fragment AO), read back after every frame; flicker over the frames (also
// against the ray-traced AO's own change) and the error of the last frame's AO against a
// ray-traced AO of the visible pathlets.
#include "ao_error.hpp"
#include "flicker.hpp"
#include "frame_sample.hpp"

#include "image_io.hpp"
#include "renderer.hpp"
#include "runtime.hpp"

#include <pathlet/scene.hpp>

#include <optional>
#include <string>
#include <vector>

namespace pathlet::quality {

struct QualityOptions {
    std::string graph_path;         // a graph file (resolve shipped names first)
    std::vector<std::string> sets;  // --set overrides
    glm::ivec2 size{320, 180};
    std::optional<TimeRange> time;  // at least two frames; none: default_quality_time(scene), said on stderr
    int rays = 256;                 // ray-traced AO: rays per pixel
    float max_distance = 10;        // ray length in line widths
    float depth_tolerance = 0.002f; // flicker: largest change of linear depth that counts as unchanged
    int flicker_rays = 256;         // ray-traced AO of every frame, for the flicker against its change (0: off)
    // Whether a pixel's own line occludes it in the ray-traced AO (issue 13's reference). Off:
    // the G-buffer's point lies inside its own tube wherever the line is inclined to the view
    // (the kit moves the tube's depth along the view axis, not the normal: 17 % of the
    // phantom's pixels at t = 9 s), and every ray from there met the tube's inside.
    bool own_line = false;
    // Where the reference's rays start: false = where the pixel's ray meets its own line's round
    // tube, with that tube's normal (the surface the pixel shows); true = the G-buffer's linear
    // depth and normal, as before (the kit's tube depth moves along the view axis and halos are
    // pushed back by up to halo_depth, so a halo pixel's point can lie inside the tubes behind it).
    bool gbuffer_point = false;
    std::string work_dir;           // where the patched copy of the graph lives while it runs
};

struct QualityResult {
    std::string graph;        // the graph's name
    std::string not_measured; // non-empty: why this graph has nothing to measure (no AO)
    size_t frames = 0;
    double first_time = 0, last_time = 0;
    FlickerStats flicker;
    ReferenceFlicker reference_flicker;  // with flicker_rays > 0
    AoError error;                  // of the last frame, abs_error per pixel
    FrameSample last;               // the last frame's AO, line ids and depth
    std::vector<float> reference;   // ray-traced AO of the last frame (1 on background)
    float reach = 0;                // ray length in world units
    size_t segments = 0;            // tube segments traced
};

// Throws GraphError (bad graph or --set), std::invalid_argument (fewer than two frames) and
// whatever rendering throws. The patched graph file is removed however it ends.
QualityResult measure_quality(Runtime& rt, const Scene& scene, const QualityOptions& opt);
// The limits of the options (rays >= 1, flicker rays >= 0, at least two frames), checked before
// any work by every caller: std::invalid_argument naming the option.
void check_quality_options(const QualityOptions& opt);

// The per-pixel error as a picture: white 0, red >= 0.5, light grey background.
Image error_image(const FrameSample& f, const std::vector<float>& abs_error);
// An AO map (the frame's or the reference) as grey, 1 = white; light grey background.
Image ao_image(const FrameSample& f, const std::vector<float>& ao);

}  // namespace pathlet::quality
