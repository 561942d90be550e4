#include "oit_metric.hpp"

#include "graph/graph_model.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace pathlet::oit_test {

MetricGraph metric_graph(const std::string& shipped_graph, const std::string& scratch_dir) {
    // The graph as merged from its bases: the passes it inherits are edited too.
    nlohmann::json g = expanded_graph_json(shipped_graph);
    MetricGraph m;
    m.front_alpha_name = "metric_front_alpha";
    g["resources"][m.front_alpha_name] = {{"format", "r16f"}};
    for (auto& p : g["passes"]) {
        if (p["type"] != "resolve_list") continue;
        p["outputs"]["front_alpha"] = m.front_alpha_name;
        const bool lit = p.contains("inputs") && (p["inputs"].contains("ao") || p["inputs"].contains("records"));
        if (lit) {  // AO applied in the resolve: bind the unlit composite
            m.unlit_name = "metric_unlit";
            g["resources"][m.unlit_name] = {{"format", "rgba8"}};
            p["outputs"]["unlit"] = m.unlit_name;
        } else {
            m.unlit_name = p["outputs"]["color"];  // resolve writes the unlit OIT colour
        }
    }
    if (m.unlit_name.empty()) throw std::runtime_error(shipped_graph + ": no resolve_list pass");
    // Outputs live to the end of the frame; a resource nobody reads could share its texture
    // with a later one of the same format (pooling) and be overwritten before it is read.
    for (const std::string& r : {m.front_alpha_name, m.unlit_name}) g["outputs"].push_back({{"resource", r}});
    m.final_name = g["outputs"][0]["resource"];
    g["outputs"][0].erase("capture");
    m.path = (std::filesystem::path(scratch_dir) / (std::filesystem::path(shipped_graph).stem().string() + "_metric.json"))
                 .string();
    std::ofstream(m.path) << g.dump(2);
    return m;
}

namespace {
double luma(const Image& img, int x, int y) {
    return 0.2126 * img.at(x, y, 0) + 0.7152 * img.at(x, y, 1) + 0.0722 * img.at(x, y, 2);
}
}  // namespace

Artefact measure_artefact(const Frame& f, const MetricGraph& g) {
    const Image &fin = f[g.final_name], &unlit = f[g.unlit_name], &front = f[g.front_alpha_name];
    Artefact a;
    double sum = 0, opaque = 0;
    size_t opaque_pixels = 0;
    for (int y = 0; y < fin.height; ++y)
        for (int x = 0; x < fin.width; ++x) {
            float fa = front.at(x, y, 0);
            if (fa >= 0.5f) opaque += luma(unlit, x, y) - luma(fin, x, y), ++opaque_pixels;
            if (!(fa > 0.0f && fa < 0.5f)) continue;
            sum += luma(unlit, x, y) - luma(fin, x, y);
            ++a.pixels;
        }
    a.darkening = a.pixels ? sum / double(a.pixels) : 0.0;
    a.opaque_darkening = opaque_pixels ? opaque / double(opaque_pixels) : 0.0;
    return a;
}

}  // namespace pathlet::oit_test
