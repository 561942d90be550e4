// "Did you mean": restricted Damerau-Levenshtein (optimal string alignment) distance,
// case-insensitive, accepted when small relative to the word's length.
#include "graph_internal.hpp"

#include <algorithm>
#include <cctype>

namespace pathlet {

namespace {

std::string lower(std::string s) {
    for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

size_t osa_distance(const std::string& a, const std::string& b) {
    const size_t n = a.size(), m = b.size();
    std::vector<std::vector<size_t>> d(n + 1, std::vector<size_t>(m + 1));
    for (size_t i = 0; i <= n; ++i) d[i][0] = i;
    for (size_t j = 0; j <= m; ++j) d[0][j] = j;
    for (size_t i = 1; i <= n; ++i)
        for (size_t j = 1; j <= m; ++j) {
            size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);  // transposition
        }
    return d[n][m];
}

}  // namespace

std::string closest_match(const std::string& word, const std::vector<std::string>& candidates) {
    // One edit per three characters (at least one): "raduis" -> "radius", but "blur" !-> "bloom".
    const size_t threshold = std::max<size_t>(1, word.size() / 3);
    const std::string w = lower(word);
    std::string best;
    size_t best_d = threshold + 1;
    for (const auto& c : candidates) {
        size_t d = osa_distance(w, lower(c));
        if (d < best_d) {  // ties keep the first candidate, so results are stable
            best_d = d;
            best = c;
        }
    }
    return best;
}

namespace graph_detail {

std::string join(const std::vector<std::string>& v, const char* sep) {
    std::string out;
    for (size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + v[i];
    return out;
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates,
                         const std::string& prefix) {
    std::string m = closest_match(word, candidates);
    return m.empty() ? "" : " (did you mean '" + prefix + m + "'?)";
}

std::string pointer_escape(const std::string& key) {
    std::string out;
    for (char c : key) {
        if (c == '~') out += "~0";
        else if (c == '/') out += "~1";
        else out += c;
    }
    return out;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

}  // namespace graph_detail
}  // namespace pathlet
