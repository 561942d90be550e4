// The SDK's text helpers (pathlet/text.hpp): one copy for the SDK and the engine alike.
#include <pathlet/text.hpp>

#include <algorithm>
#include <cctype>
#include <vector>

namespace pathlet::text {

std::string join(const std::vector<std::string>& items, std::string_view sep) {
    std::string out;
    for (size_t i = 0; i < items.size(); ++i) {
        if (i) out += sep;
        out += items[i];
    }
    return out;
}

namespace {

std::string lower(std::string s) {
    for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// Optimal string alignment distance: edits plus adjacent transpositions.
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
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[n][m];
}

}  // namespace

std::string closest_match(const std::string& word, const std::vector<std::string>& candidates) {
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

std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates,
                         const std::string& prefix) {
    std::string m = closest_match(word, candidates);
    return m.empty() ? "" : " (did you mean '" + prefix + m + "'?)";
}

}  // namespace pathlet::text
