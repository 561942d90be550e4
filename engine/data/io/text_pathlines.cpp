// Plain-text pathlines: one line per row, "x y z x y z ...". Samples lie on a uniform
// time grid (k * time_step). Lines released late are padded at the front with copies of
// their seed point: those copies are dropped and the line's time starts at
// (number of copies) * time_step. Velocity comes from finite differences (repair step).
#include "byte_reader.hpp"
#include "pathline_formats.hpp"

namespace pathlet::io {

Pathlines read_text_rows(std::string_view bytes, const std::string& file, const LoadOptions& opts, LoadReport& report) {
    const double dt = opts.time_step > 0 ? opts.time_step : 0.01;
    report.format = "plain-text pathline rows";
    Pathlines pl;
    pl.position.reserve(bytes.size() / 24);
    pl.time.reserve(bytes.size() / 24);
    Cursor c(bytes, file);
    size_t raw_samples = 0, late_lines = 0, late_copies = 0;
    std::vector<float> row;
    while (!c.at_end()) {
        size_t line_no = c.line();
        auto text = c.rest_of_line();
        size_t f = text.find_first_not_of(" \t\r");
        if (f == std::string_view::npos || text[f] == '#') continue;  // blank or comment row
        Cursor rc(text, file);
        row.clear();
        for (auto t = rc.token(); !t.empty(); t = rc.token()) {
            float v;
            if (!parse_number(t, v))
                fail_at(file, at_line(line_no), "'" + std::string(t.substr(0, 40)) + "' is not a number (expected rows of x y z ...)");
            row.push_back(v);
        }
        
        if (row.size() % 3 != 0)
            fail_at(file, at_line(line_no), std::to_string(row.size()) + " numbers is not a multiple of 3 (x y z per sample; row truncated?)");
        size_t n = row.size() / 3;
        raw_samples += n;
        size_t skip = 0;  // leading copies of the seed point = late release
        while (skip + 1 < n && row[3 * skip] == row[3 * skip + 3] && row[3 * skip + 1] == row[3 * skip + 4] &&
               row[3 * skip + 2] == row[3 * skip + 5])
            ++skip;
        if (skip) { ++late_lines; late_copies += skip; }
        uint32_t first = uint32_t(pl.position.size());
        for (size_t k = skip; k < n; ++k) {
            pl.position.push_back({row[3 * k], row[3 * k + 1], row[3 * k + 2]});
            pl.time.push_back(float(double(k) * dt));
        }
        pl.lines.push_back({first, uint32_t(n - skip)});
    }
    report.warnings.push_back("plain text has no time: sample k is at k * " + std::to_string(dt) + " s" +
                              (opts.time_step > 0 ? "" : " (the default; give the real one with --time-step SECONDS, in Python load(..., time_step=SECONDS))"));
    if (late_copies)
        report.warnings.push_back("late release: dropped " + std::to_string(late_copies) + " leading copies of the seed point in " +
                                  std::to_string(late_lines) + " lines (" + std::to_string(raw_samples) + " raw samples)");
    if (pl.lines.empty()) report.warnings.push_back("the file holds no lines: empty pathline set");
    if (opts.time_step > 0) pl.units.time = "s";  // the default step is a guess: no unit shown for it
    repair_pathlines(pl, report, file);
    return pl;
}

}  // namespace pathlet::io
