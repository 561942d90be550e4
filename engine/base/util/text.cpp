#include "util/text.hpp"

#include "util/input_limits.hpp"

#include <pathlet/scene.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace pathlet::text {


std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string piece;
    while (std::getline(in, piece, sep))
        if (!piece.empty()) out.push_back(piece);
    return out;
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

std::string shell_quote(const std::string& word) {
    const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("@%+=:,./_-", c) != nullptr;
    });
    if (plain) return word;
    std::string q = "'";
    for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string shell_command(const std::vector<std::string>& words) {
    std::string out;
    for (const auto& w : words) out += (out.empty() ? "" : " ") + shell_quote(w);
    return out;
}

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
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


nlohmann::json parse_json(const std::string& text) {
    const int limit = io::max_json_depth();
    if (io::JsonDepth d = io::json_nesting_depth(text, limit); d.first_too_deep != size_t(-1))
        throw JsonError("nesting deeper than " + std::to_string(limit) +
                            " levels (arrays/objects); PATHLET_MAX_JSON_DEPTH raises the cap",
                        d.first_too_deep);
    try {
        return nlohmann::json::parse(text, nullptr, true, /*ignore_comments=*/true);
    } catch (const nlohmann::json::parse_error& e) {
        std::string what = e.what();
        size_t at = what.find(": ", what.find("parse error"));  // drop "[json.exception...] parse error at ...: "
        std::string msg = at == std::string::npos ? what : what.substr(at + 2);
        if (msg.rfind("syntax error", 0) != 0) msg = "syntax error: " + msg;
        throw JsonError(msg, e.byte ? e.byte - 1 : 0);  // e.byte is 1-based: the last byte read
    } catch (const nlohmann::json::out_of_range& e) {
        // A number literal beyond double's range (1e400). nlohmann gives no position: find the token.
        std::string what = e.what();
        size_t q = what.find('\'');
        std::string token = q == std::string::npos ? "" : what.substr(q + 1, what.rfind('\'') - q - 1);
        throw JsonError("number out of range: " + (token.empty() ? what : "'" + token + "'") +
                            " does not fit a double (|x| < 1.8e308)",
                        token.empty() ? std::string::npos : text.find(token));
    }
}

std::string line_column(const std::string& text, size_t offset) {
    offset = std::min(offset, text.size());
    const long line = 1 + std::count(text.begin(), text.begin() + long(offset), '\n');
    const size_t nl = offset == 0 ? std::string::npos : text.rfind('\n', offset - 1);
    const size_t column = offset - (nl == std::string::npos ? 0 : nl + 1) + 1;
    return std::to_string(line) + ":" + std::to_string(column);
}

std::string read_json_text(const std::string& path, const std::string& what) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw DataError(path + ": is a directory, not " + what);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw DataError(path + ": cannot open " + what + ": " + std::strerror(errno));
    const size_t cap = io::max_json_bytes();
    std::string bytes;
    char chunk[1 << 16];
    while (bytes.size() <= cap && in.read(chunk, sizeof chunk).gcount() > 0) bytes.append(chunk, size_t(in.gcount()));
    if (bytes.size() > cap)
        throw DataError(path + ": " + what + " is larger than " +
                        (cap % (1 << 20) ? std::to_string(cap) + " bytes" : std::to_string(cap >> 20) + " MiB") +
                        "; PATHLET_MAX_JSON_BYTES raises the cap");
    return bytes;
}

nlohmann::json parse_json_of(const std::string& path, const std::string& text, const std::string& what) {
    try {
        return parse_json(text);
    } catch (const JsonError& e) {
        const std::string at = e.offset == std::string::npos ? "" : ":" + line_column(text, e.offset);
        throw DataError(path + at + ": not valid JSON (" + what + "): " + e.what());
    }
}

nlohmann::json read_json_file(const std::string& path, const std::string& what) {
    return parse_json_of(path, read_json_text(path, what), what);
}

}  // namespace pathlet::text
