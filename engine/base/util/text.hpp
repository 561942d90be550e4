// The engine's text helpers: splitting, quoting (for messages, POSIX shells and CSV), JSON
// pointers, and JSON files read with the limits every input file gets. One copy of each, so a
// fix (a quote inside an argument, a file too deep) reaches every caller.
//
// Lists in messages and "did you mean" (join, closest_match, did_you_mean) are in
// <pathlet/text.hpp>, installed with the SDK, so passes, the SDK and the engine share one copy.
// This header stands on its own and does not re-export it; a file that uses those includes
// <pathlet/text.hpp> itself.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace pathlet::text {

// ---- lists ------------------------------------------------------------------------------
// Pieces between `sep`; empty pieces are dropped ("a,,b" -> a, b).
std::vector<std::string> split(const std::string& s, char sep);

// ---- quoting ----------------------------------------------------------------------------
std::string quoted(const std::string& s);  // 'x', for messages
// One word for a POSIX shell: unchanged when it holds only characters no shell treats
// specially, else in single quotes with each ' written as '\'' ("it's" -> 'it'\''s'; "" -> '').
std::string shell_quote(const std::string& word);
// Words joined by spaces, each shell_quote'd: a command line a user can paste.
std::string shell_command(const std::vector<std::string>& words);
// One CSV field (RFC 4180): in double quotes, with " doubled, when it holds , " CR or LF.
std::string csv_field(const std::string& s);
// RFC 6901 JSON pointer token: "~" -> "~0", "/" -> "~1".
std::string pointer_escape(const std::string& key);

// ---- JSON -------------------------------------------------------------------------------
// A JSON text that cannot be read: the reason and the byte offset it was found at (npos: none).
struct JsonError : std::runtime_error {
    JsonError(const std::string& reason, size_t offset) : std::runtime_error(reason), offset(offset) {}
    size_t offset;
};
// Parses JSON with // and /* */ comments. Before parsing, the nesting is checked against
// io::max_json_depth() (a deeper value would overflow the stack when walked); numbers beyond a
// double's range are refused with the token. Throws JsonError.
nlohmann::json parse_json(const std::string& text);
// "LINE:COLUMN" (1-based) of a byte offset, for messages.
std::string line_column(const std::string& text, size_t offset);
// A regular file's bytes, at most io::max_json_bytes() of them (PATHLET_MAX_JSON_BYTES).
// Throws DataError "PATH: cannot read WHAT: reason" / "is a directory" / "is larger than".
std::string read_json_text(const std::string& path, const std::string& what);
// parse_json of a file's text; throws DataError "PATH:LINE:COL: not valid JSON (WHAT): reason".
nlohmann::json parse_json_of(const std::string& path, const std::string& text, const std::string& what);
// read_json_text + parse_json_of.
nlohmann::json read_json_file(const std::string& path, const std::string& what);

}  // namespace pathlet::text
