// Plots written by pathlet itself (plain SVG, no scripts), so every results folder has a
// picture even where Python is not installed (a cluster node); `pathlet bench --plots` and
// `python3 -m pathlet.plot` draw the publication figures (PNG, PDF) with Matplotlib, with the
// same colour per pass.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace pathlet::cli::bench {

struct Bar {
    std::string label;                                  // "isl 1280x720" (also the group's data-label)
    std::string group;                                  // bars of one group (size) stand together
    std::vector<std::pair<std::string, double>> parts;  // pass name, median ms (stacked left to right)
    double frame_median = -1, frame_p5 = 0, frame_p95 = 0;  // the whole frame; < 0: not drawn
};
// One horizontal bar per run in its own labelled row (no label can overlap another), groups
// apart, the frame's median and p5..p95 at the end; one <g class="bar"> per bar; a legend.
std::string stacked_bars_svg(const std::string& title, const std::vector<Bar>& bars);

// Pass name -> colour: shipped passes fixed, others hashed (FNV-1a) into the colours left
// free, the next free one on a collision: the rule and table of pathlet/pass_colors.json (the
// Python package's), which pathlet/plot.py follows too.
std::map<std::string, std::string> pass_colors(const std::vector<std::string>& names);

struct Series {
    std::string label;
    std::vector<double> x, median, p5, p95;  // one point per swept value
};
// Frame time against the swept parameter, a p5..p95 whisker at every point.
std::string line_chart_svg(const std::string& title, const std::string& x_label, const std::vector<Series>& series);

}  // namespace pathlet::cli::bench
