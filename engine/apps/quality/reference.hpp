#pragma once
// `pathlet quality GRAPH --reference REFGRAPH` as a function (also Python's quality(...,
// reference=...)): both graphs rendered over the same times at the same size with the same
// camera (the data's framing) and --set overrides, their pictures (each graph's first output)
// compared frame by frame over the pixels either covers (its coverage: the depth the wall pass
// reads, or a line pass's depth output), with image_metrics.hpp's measures pooled over the
// frames and the flicker against the reference's own change. Optionally the difference images.
// Frames are measured as the reference renders them: the tested graph's wait compressed in a
// temporary file, so memory does not grow with the frames. A reference with incomplete frames
// (fragments dropped or cut) is refused; the tested graph's are named.
#include "image_metrics.hpp"

#include "renderer.hpp"
#include "runtime.hpp"

#include <pathlet/scene.hpp>

#include <optional>
#include <string>
#include <vector>

namespace pathlet::quality {

struct ReferenceOptions {
    std::string graph_path, reference_path;  // graph files (shipped names resolved by the caller)
    std::vector<std::string> sets;           // --set overrides, given to both graphs
    std::vector<std::string> reference_sets; // the reference's own, after `sets` (Python's Graph.set)
    glm::ivec2 size{320, 180};
    std::optional<TimeRange> time;  // none: default_quality_time(scene), said on stderr
    int reference_ssaa = 1;         // the reference rendered with N x N samples a pixel (render --ssaa N), box-filtered
    std::string out_dir;            // non-empty: difference and FLIP images (and the last pair) written here
    double ppd = kFlipPpd;          // FLIP's observer: pixels per degree of visual angle
};

struct ReferenceResult {
    std::string graph, reference;
    size_t frames = 0;
    double first_time = 0, last_time = 0;
    ImageMetrics metrics;                  // pooled over the frames
    std::vector<ImageMetrics> per_frame;
    std::optional<FlickerVsReference> flicker;  // with two frames or more
    AaFigures aa, reference_aa;            // aa_metric's figures against the reference, pooled over frames;
                                           // the reference's speckles (its rms 0)
    std::vector<std::string> images;       // files written to out_dir
    std::vector<size_t> incomplete_frames;  // of the tested graph (fragments dropped), ascending
};

// Throws GraphError (bad graph or --set), std::invalid_argument (a graph without a coverage or
// with an output that is no colour image), std::runtime_error (a reference with incomplete
// frames) and whatever rendering throws.
ReferenceResult measure_against_reference(Runtime& rt, const Scene& scene, const ReferenceOptions& opt);
// What to say when the tested graph rendered incomplete frames, else "".
std::string incomplete_frames_note(const ReferenceResult& r);

}  // namespace pathlet::quality
