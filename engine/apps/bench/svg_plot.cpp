#include "svg_plot.hpp"

#include "bench/pass_colors_json.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace pathlet::cli::bench {
namespace {

// Series of a sweep chart (graph x size); passes have their own colours (pass_colors).
const char* kPalette[] = {"#1f3b73", "#c0392b", "#2e8b57", "#8e44ad", "#d35400", "#16a085", "#7f8c8d", "#b7950b",
                          "#2c3e50", "#a93226"};

std::string esc(const std::string& s) {
    std::string o;
    for (char c : s) {
        if (c == '<') o += "&lt;";
        else if (c == '>') o += "&gt;";
        else if (c == '&') o += "&amp;";
        else if (c == '"') o += "&quot;";
        else o += c;
    }
    return o;
}

std::string num(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.2f", v);
    return b;
}

// A "nice" axis maximum and tick step for values up to `top`.
std::pair<double, double> axis(double top) {
    if (!(top > 0)) top = 1;
    double step = std::pow(10.0, std::floor(std::log10(top / 5)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (top / (step * m) <= 6) {
            step *= m;
            break;
        }
    return {std::ceil(top / step) * step, step};
}

std::string header(int w, int h, const std::string& title) {
    return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(w) + "\" height=\"" +
           std::to_string(h) + "\" viewBox=\"0 0 " + std::to_string(w) + " " + std::to_string(h) +
           "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
           "<text x=\"" + std::to_string(w / 2) + "\" y=\"20\" text-anchor=\"middle\" font-size=\"15\">" + esc(title) +
           "</text>\n";
}

std::string y_axis(double x0, double y0, double plot_h, double plot_w, double top, double step, const char* label) {
    std::string s;
    for (double v = 0; v <= top + step * 0.01; v += step) {
        double y = y0 - v / top * plot_h;
        s += "<line x1=\"" + num(x0) + "\" x2=\"" + num(x0 + plot_w) + "\" y1=\"" + num(y) + "\" y2=\"" + num(y) +
             "\" stroke=\"#ddd\"/>\n<text x=\"" + num(x0 - 6) + "\" y=\"" + num(y + 4) +
             "\" text-anchor=\"end\">" + num(v) + "</text>\n";
    }
    s += "<text transform=\"translate(16," + num(y0 - plot_h / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
         std::string(label) + "</text>\n";
    return s;
}

}  // namespace

std::map<std::string, std::string> pass_colors(const std::vector<std::string>& names) {
    // The rule and its table are those of pathlet/pass_colors.json, which pathlet/plot.py reads too.
    static const nlohmann::json table = nlohmann::json::parse(kPassColorsJson);
    const auto& palette = table.at("palette");
    const auto& places = table.at("places");
    const size_t n = palette.size();
    std::vector<bool> taken(n, false);
    for (const auto& name : names)
        if (places.contains(name)) taken[places[name].get<size_t>()] = true;
    std::map<std::string, std::string> out;
    for (const auto& name : names) {
        if (out.count(name)) continue;
        if (places.contains(name)) {
            out[name] = palette[places[name].get<size_t>()];
            continue;
        }
        uint32_t h = 0x811C9DC5u;
        for (unsigned char c : name) h = (h ^ c) * 0x01000193u;
        size_t i = h % n;
        for (size_t k = 0; k < n && taken[i]; ++k) i = (i + 1) % n;
        taken[i] = true;
        out[name] = palette[i];
    }
    return out;
}

std::string stacked_bars_svg(const std::string& title, const std::vector<Bar>& bars) {
    std::vector<std::string> names;  // legend order: first seen
    double top = 0;
    size_t longest = 8;
    for (const auto& b : bars) {
        double sum = 0;
        for (const auto& [n, v] : b.parts) {
            sum += v;
            if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
        }
        top = std::max({top, sum, b.frame_p95});
        longest = std::max(longest, b.label.size());
    }
    const auto colors = pass_colors(names);
    auto [xmax, step] = axis(top * 1.12);
    // Rows of 24 px, 12 px more between groups; the label column as wide as the longest label.
    const double row = 24, bh = 16, gap = 12, label_w = 12 + 6.6 * double(longest), x0 = label_w + 10, y0 = 44;
    const double plot_w = 520;
    double y = y0;
    std::vector<double> ys;
    for (size_t i = 0; i < bars.size(); ++i) {
        if (i > 0 && bars[i].group != bars[i - 1].group) y += gap;
        ys.push_back(y);
        y += row;
    }
    const double plot_h = std::max(y - y0, 40.0);
    const int w = int(x0 + plot_w + 200), h = int(std::max(y0 + plot_h + 50, 60.0 + double(names.size()) * 18));
    std::string s = header(w, h, title);
    auto px = [&](double v) { return x0 + v / xmax * plot_w; };
    for (double v = 0; v <= xmax + step * 0.01; v += step)
        s += "<line x1=\"" + num(px(v)) + "\" x2=\"" + num(px(v)) + "\" y1=\"" + num(y0 - 4) + "\" y2=\"" +
             num(y0 + plot_h) + "\" stroke=\"#ddd\"/>\n<text x=\"" + num(px(v)) + "\" y=\"" + num(y0 + plot_h + 16) +
             "\" text-anchor=\"middle\">" + num(v) + "</text>\n";
    s += "<text x=\"" + num(x0 + plot_w / 2) + "\" y=\"" + num(y0 + plot_h + 36) +
         "\" text-anchor=\"middle\">median ms per frame (passes stacked; | and whisker: frame median, p5..p95)</text>\n";
    for (size_t i = 0; i < bars.size(); ++i) {
        const Bar& b = bars[i];
        const double by = ys[i] + (row - bh) / 2;
        double x = 0, sum = 0;
        s += "<g class=\"bar\" data-label=\"" + esc(b.label) + "\">\n<text x=\"" + num(x0 - 8) + "\" y=\"" +
             num(by + bh - 4) + "\" text-anchor=\"end\">" + esc(b.label) + "</text>\n";
        for (const auto& [n, v] : b.parts) {
            s += "<rect x=\"" + num(px(x)) + "\" y=\"" + num(by) + "\" width=\"" + num(px(x + v) - px(x)) +
                 "\" height=\"" + num(bh) + "\" fill=\"" + colors.at(n) + "\"><title>" +
                 esc(b.label + ": " + n + " " + num(v) + " ms") + "</title></rect>\n";
            x += v;
            sum += v;
        }
        double end = sum;
        if (b.frame_median >= 0) {
            const double cy = by + bh / 2;
            s += "<line x1=\"" + num(px(b.frame_p5)) + "\" x2=\"" + num(px(b.frame_p95)) + "\" y1=\"" + num(cy) +
                 "\" y2=\"" + num(cy) + "\" stroke=\"#222\"/><line x1=\"" + num(px(b.frame_median)) + "\" x2=\"" +
                 num(px(b.frame_median)) + "\" y1=\"" + num(by - 2) + "\" y2=\"" + num(by + bh + 2) +
                 "\" stroke=\"#222\" stroke-width=\"2\"/>\n";
            end = std::max(end, b.frame_p95);
        }
        s += "<text x=\"" + num(px(end) + 6) + "\" y=\"" + num(by + bh - 4) + "\" font-size=\"11\">" +
             num(b.frame_median >= 0 ? b.frame_median : sum) + " ms</text>\n</g>\n";
    }
    s += "<line x1=\"" + num(x0) + "\" x2=\"" + num(x0) + "\" y1=\"" + num(y0 - 4) + "\" y2=\"" + num(y0 + plot_h) +
         "\" stroke=\"black\"/>\n";
    for (size_t i = 0; i < names.size(); ++i) {
        double lx = x0 + plot_w + 24, ly = y0 + 10 + i * 18.0;
        s += "<rect x=\"" + num(lx) + "\" y=\"" + num(ly - 10) + "\" width=\"12\" height=\"12\" fill=\"" +
             colors.at(names[i]) + "\"/><text x=\"" + num(lx + 18) + "\" y=\"" + num(ly) + "\">" + esc(names[i]) +
             "</text>\n";
    }
    return s + "</svg>\n";
}

std::string line_chart_svg(const std::string& title, const std::string& x_label, const std::vector<Series>& series) {
    double xmin = 1e300, xmax = -1e300, top = 0;
    for (const auto& se : series)
        for (size_t i = 0; i < se.x.size(); ++i) {
            xmin = std::min(xmin, se.x[i]);
            xmax = std::max(xmax, se.x[i]);
            top = std::max(top, se.p95[i]);
        }
    if (!(xmax > xmin)) xmax = xmin + 1;
    auto [ymax, step] = axis(top);
    const double x0 = 70, y0 = 330, plot_h = 280, plot_w = 480;
    std::string s = header(int(x0 + plot_w + 220), 380, title);
    s += y_axis(x0, y0, plot_h, plot_w, ymax, step, "frame ms (median, p5..p95)");
    auto px = [&](double v) { return x0 + 10 + (v - xmin) / (xmax - xmin) * (plot_w - 20); };
    auto py = [&](double v) { return y0 - v / ymax * plot_h; };
    std::vector<double> ticks;
    for (const auto& se : series) ticks.insert(ticks.end(), se.x.begin(), se.x.end());
    std::sort(ticks.begin(), ticks.end());
    ticks.erase(std::unique(ticks.begin(), ticks.end()), ticks.end());
    for (double t : ticks) {
        char b[32];
        std::snprintf(b, sizeof b, "%g", t);
        s += "<text x=\"" + num(px(t)) + "\" y=\"" + num(y0 + 16) + "\" text-anchor=\"middle\">" + b + "</text>\n";
    }
    s += "<text x=\"" + num(x0 + plot_w / 2) + "\" y=\"" + num(y0 + 36) + "\" text-anchor=\"middle\">" +
         esc(x_label) + "</text>\n";
    for (size_t k = 0; k < series.size(); ++k) {
        const Series& se = series[k];
        const char* col = kPalette[k % 10];
        s += "<g class=\"series\" data-label=\"" + esc(se.label) + "\">\n<polyline fill=\"none\" stroke=\"" +
             std::string(col) + "\" stroke-width=\"2\" points=\"";
        for (size_t i = 0; i < se.x.size(); ++i) s += num(px(se.x[i])) + "," + num(py(se.median[i])) + " ";
        s += "\"/>\n";
        for (size_t i = 0; i < se.x.size(); ++i)
            s += "<line x1=\"" + num(px(se.x[i])) + "\" x2=\"" + num(px(se.x[i])) + "\" y1=\"" + num(py(se.p5[i])) +
                 "\" y2=\"" + num(py(se.p95[i])) + "\" stroke=\"" + col + "\"/><circle cx=\"" + num(px(se.x[i])) +
                 "\" cy=\"" + num(py(se.median[i])) + "\" r=\"3\" fill=\"" + col + "\"/>\n";
        s += "</g>\n<rect x=\"" + num(x0 + plot_w + 16) + "\" y=\"" + num(40 + k * 18.0) +
             "\" width=\"12\" height=\"12\" fill=\"" + col + "\"/><text x=\"" + num(x0 + plot_w + 34) + "\" y=\"" +
             num(50 + k * 18.0) + "\">" + esc(se.label) + "</text>\n";
    }
    return s + "</svg>\n";
}

}  // namespace pathlet::cli::bench
