// Plots written by pathlet itself (plain SVG, no scripts): stacked per-pass bars and sweep lines.
#pragma once

#include <string>
#include <vector>

namespace pathlet::cli::bench {

struct Bar {
    std::string label;                                  // "isl 1280x720"
    std::vector<std::pair<std::string, double>> parts;  // pass name, median ms (stacked bottom-up)
};
// One <g class="bar"> per bar; passes keep their colour across bars; a legend names them.
std::string stacked_bars_svg(const std::string& title, const std::vector<Bar>& bars);

struct Series {
    std::string label;
    std::vector<double> x, median, p5, p95;  // one point per swept value
};
// Frame time against the swept parameter, a p5..p95 whisker at every point.
std::string line_chart_svg(const std::string& title, const std::string& x_label, const std::vector<Series>& series);

}  // namespace pathlet::cli::bench
