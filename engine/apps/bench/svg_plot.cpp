#include "svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace pathlet::cli::bench {
namespace {

const char* kPalette[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948",
                          "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"};

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

std::string stacked_bars_svg(const std::string& title, const std::vector<Bar>& bars) {
    std::vector<std::string> names;  // legend order: first seen
    double top = 0;
    for (const auto& b : bars) {
        double sum = 0;
        for (const auto& [n, v] : b.parts) {
            sum += v;
            if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
        }
        top = std::max(top, sum);
    }
    auto [ymax, step] = axis(top);
    const double bw = 56, gap = 28, x0 = 70, y0 = 330, plot_h = 280;
    const double plot_w = std::max(200.0, bars.size() * (bw + gap) + gap);
    const int legend_w = 200;
    // Room below for the slanted labels, at the right for the legend.
    const int w = int(x0 + plot_w + legend_w + 60), h = int(y0 + 120);
    std::string s = header(w, std::max(h, int(60 + names.size() * 18)), title);
    s += y_axis(x0, y0, plot_h, plot_w, ymax, step, "median ms per frame");
    for (size_t i = 0; i < bars.size(); ++i) {
        const Bar& b = bars[i];
        double x = x0 + gap + i * (bw + gap), y = y0, sum = 0;
        s += "<g class=\"bar\" data-label=\"" + esc(b.label) + "\">\n";
        for (const auto& [n, v] : b.parts) {
            size_t ci = std::find(names.begin(), names.end(), n) - names.begin();
            double hgt = v / ymax * plot_h;
            y -= hgt;
            sum += v;
            s += "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(bw) + "\" height=\"" + num(hgt) +
                 "\" fill=\"" + kPalette[ci % 10] + "\"><title>" + esc(b.label + ": " + n + " " + num(v) + " ms") +
                 "</title></rect>\n";
        }
        s += "<text x=\"" + num(x + bw / 2) + "\" y=\"" + num(y - 4) + "\" text-anchor=\"middle\">" + num(sum) +
             "</text>\n<text transform=\"translate(" + num(x + bw / 2) + "," + num(y0 + 14) +
             ") rotate(20)\" font-size=\"11\">" + esc(b.label) + "</text>\n</g>\n";
    }
    s += "<line x1=\"" + num(x0) + "\" x2=\"" + num(x0) + "\" y1=\"" + num(y0 - plot_h) + "\" y2=\"" + num(y0) +
         "\" stroke=\"black\"/>\n";
    for (size_t i = 0; i < names.size(); ++i) {
        double lx = x0 + plot_w + 16, ly = 50 + i * 18.0;
        s += "<rect x=\"" + num(lx) + "\" y=\"" + num(ly - 10) + "\" width=\"12\" height=\"12\" fill=\"" +
             kPalette[i % 10] + "\"/><text x=\"" + num(lx + 18) + "\" y=\"" + num(ly) + "\">" + esc(names[i]) +
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
