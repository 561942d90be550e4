// Text helpers of the SDK, for messages: lists and "did you mean". Passes may use them for
// their own errors; the engine's other text helpers (engine/base/util/text.hpp) sit beside them.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace pathlet::text {

std::string join(const std::vector<std::string>& items, std::string_view sep = ", ");
// The candidate closest to `word` (restricted Damerau-Levenshtein, case-insensitive), or ""
// when none is within one edit per three characters ("raduis" -> "radius", "blur" !-> "bloom").
std::string closest_match(const std::string& word, const std::vector<std::string>& candidates);
// " (did you mean 'PREFIXx'?)" or "": appended to "unknown ..." messages.
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates,
                         const std::string& prefix = "");

}  // namespace pathlet::text
