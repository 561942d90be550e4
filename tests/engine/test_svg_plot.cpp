// The SVG bars bench writes into every results folder: every run in its own labelled row
// (the table-3 plot had overlapping slanted labels), sizes apart, and no two passes sharing a
// colour (its legend had repeated colours past ten passes).
#include "bench/svg_plot.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <set>

using namespace pathlet::cli::bench;

namespace {

const std::vector<std::string> kShipped = {"gbuffer", "gauss_pyramid", "lineao", "bilateral", "wall", "edge_aa",
                                           "overlay", "isl", "temporal_ao", "clear_list", "fill_list",
                                           "resolve_list", "fade_core", "geometric_fade"};

std::vector<Bar> table3_bars() {
    std::vector<Bar> bars;
    const std::vector<std::pair<std::string, std::vector<std::string>>> graphs = {
        {"V1 LineAO", {"gbuffer", "gauss_pyramid", "lineao", "bilateral", "wall", "edge_aa", "overlay"}},
        {"V2 OIT", {"clear_list", "fill_list", "resolve_list", "gauss_pyramid", "lineao", "bilateral", "wall"}},
        {"V3 geometric fade", {"geometric_fade", "gauss_pyramid", "lineao", "bilateral", "wall", "edge_aa"}},
        {"ISL", {"isl", "wall", "edge_aa", "overlay"}}};
    for (const std::string size : {"1280x720", "1920x1080"})
        for (const auto& [label, passes] : graphs) {
            Bar b{label + " " + size, size, {}};
            double sum = 0;
            for (size_t i = 0; i < passes.size(); ++i) b.parts.push_back({passes[i], 5.0 + double(i)}), sum += 5.0 + double(i);
            b.frame_median = sum * 1.02, b.frame_p5 = sum, b.frame_p95 = sum * 1.1;
            bars.push_back(b);
        }
    return bars;
}

}  // namespace

TEST(SvgPlot, EveryPassHasItsOwnColourAndKeepsIt) {
    std::vector<std::string> names = kShipped;
    names.insert(names.end(), {"my_fade", "vignette", "blur"});
    const auto colors = pass_colors(names);
    std::set<std::string> distinct;
    for (const auto& n : names) distinct.insert(colors.at(n));
    EXPECT_EQ(distinct.size(), names.size()) << "two passes share a colour";
    // A pass keeps its colour whatever else is drawn (figures of different graphs compare).
    EXPECT_EQ(pass_colors({"isl", "wall"}).at("wall"), colors.at("wall"));
    EXPECT_EQ(pass_colors({"geometric_fade"}).at("geometric_fade"), colors.at("geometric_fade"));
    EXPECT_EQ(pass_colors({"my_fade"}).at("my_fade"), pass_colors({"blur", "my_fade"}).at("my_fade"));
}

TEST(SvgPlot, EveryRunIsARowOfItsOwnWithItsLabel) {
    const std::vector<Bar> bars = table3_bars();
    const std::string svg = stacked_bars_svg("table3", bars);
    // One group per run, each with its label as text, rows top to bottom without overlap.
    const std::regex group(R"re(<g class="bar" data-label="([^"]*)">\n<text x="([0-9.]+)" y="([0-9.]+)"[^>]*>([^<]*)</text>)re");
    std::vector<double> ys;
    size_t k = 0;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), group); it != std::sregex_iterator(); ++it, ++k) {
        ASSERT_LT(k, bars.size());
        EXPECT_EQ((*it)[1], bars[k].label);
        EXPECT_EQ((*it)[4], bars[k].label) << "the label is written out, not cut";
        // Right-aligned at x: room for the whole label left of the bars (~6.6 px a character).
        EXPECT_GE(std::stod((*it)[2]), 6.0 * double(bars[k].label.size())) << bars[k].label;
        ys.push_back(std::stod((*it)[3]));
    }
    ASSERT_EQ(k, bars.size()) << "a bar per run";
    for (size_t i = 1; i < ys.size(); ++i) EXPECT_GE(ys[i] - ys[i - 1], 20.0) << "rows " << i - 1 << " and " << i << " overlap";
    EXPECT_GE(ys[4] - ys[3], ys[1] - ys[0] + 8) << "the sizes stand apart";
    // Every bar segment lies inside the picture.
    const std::regex width(R"re(<svg [^>]*width="([0-9]+)")re");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(svg, m, width));
    const double w = std::stod(m[1]);
    const std::regex rect(R"re(<rect x="([0-9.]+)" y="[0-9.]+" width="([0-9.]+)")re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), rect); it != std::sregex_iterator(); ++it)
        EXPECT_LE(std::stod((*it)[1]) + std::stod((*it)[2]), w);
    // The legend: each pass once, in its colour, no colour twice.
    std::set<std::string> legend;
    const std::regex entry(R"re(<rect x="[0-9.]+" y="[0-9.]+" width="12" height="12" fill="(#[0-9a-f]{6})"/><text[^>]*>([^<]*)</text>)re");
    size_t entries = 0;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), entry); it != std::sregex_iterator(); ++it, ++entries)
        legend.insert((*it)[1]);
    EXPECT_EQ(entries, 12u) << "the twelve passes of the four graphs";
    EXPECT_EQ(legend.size(), entries) << "a colour repeats in the legend";
}
