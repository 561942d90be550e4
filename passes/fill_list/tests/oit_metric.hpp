// Variant 2's artefact, as a number: how much darker than the unlit OIT colour the final image
// is at pixels whose front fragment is faded (0 < alpha < 0.5). The study's Fig. 11b/c are this
// darkening; a graph that applies AO only where it belongs keeps it near zero.
#pragma once

#include "frame_capture.hpp"

#include <string>

namespace pathlet::oit_test {

// A copy of a shipped OIT graph whose resolve_list also writes `unlit` (when its colour is
// lit) and `front_alpha`, written beside `scratch_dir`; returns the path and the resource names.
struct MetricGraph {
    std::string path, final_name, unlit_name, front_alpha_name;
};
MetricGraph metric_graph(const std::string& shipped_graph, const std::string& scratch_dir);

struct Artefact {
    double darkening = 0;  // mean luma(unlit) - luma(final) over faded-front pixels, 0..1
    size_t pixels = 0;     // faded-front pixels
    // The same over pixels whose front fragment is opaque (alpha >= 0.5): how strong the AO is
    // where it belongs, to read the faded-front figure against.
    double opaque_darkening = 0;
};
Artefact measure_artefact(const Frame& f, const MetricGraph& g);

}  // namespace pathlet::oit_test
