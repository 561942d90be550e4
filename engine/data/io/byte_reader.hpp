// One bounds-checked cursor for every importer: whitespace tokens (counting lines, for
// text formats) and exact-length byte slices (for binary payloads, which may contain
// 0x0A). Every error names the file and a location: "line N" in text mode, else "byte N".
#pragma once

#include <pathlet/scene.hpp>

#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>

namespace pathlet::io {

[[noreturn]] inline void fail_at(const std::string& file, const std::string& where, const std::string& msg) {
    throw DataError(file + ": " + where + ": " + msg);
}
inline std::string at_byte(size_t b) { return "byte " + std::to_string(b); }
inline std::string at_line(size_t l) { return "line " + std::to_string(l); }

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

inline bool iequals(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i) {
        char x = a[i], y = b[i];
        if (x >= 'A' && x <= 'Z') x = char(x - 'A' + 'a');
        if (y >= 'A' && y <= 'Z') y = char(y - 'A' + 'a');
        if (x != y) return false;
    }
    return true;
}

// Parses a whole token as a number; false if it is not one. Accepts a leading '+'
// (VTK writes NumberOfPoints="+11047") and nan/inf.
template <class T>
bool parse_number(std::string_view s, T& out) {
    if (!s.empty() && s[0] == '+') s.remove_prefix(1);
    if (s.empty()) return false;
    auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && p == s.data() + s.size();
}

class Cursor {
public:
    Cursor(std::string_view data, std::string file, bool text_locations = true)
        : data_(data), file_(std::move(file)), text_(text_locations) {}

    size_t pos() const { return pos_; }
    size_t size() const { return data_.size(); }
    size_t remaining() const { return data_.size() - pos_; }
    bool at_end() const { return pos_ >= data_.size(); }
    size_t line() const { return line_; }
    const std::string& file() const { return file_; }
    std::string_view data() const { return data_; }
    // Binary files report byte offsets (line numbers after a binary block mean nothing).
    void set_text_locations(bool on) { text_ = on; }
    std::string where() const { return text_ ? at_line(line_) : at_byte(pos_); }

    [[noreturn]] void fail(const std::string& msg) const { fail_at(file_, where(), msg); }
    [[noreturn]] void fail_byte(size_t at, const std::string& msg) const { fail_at(file_, at_byte(at), msg); }

    void skip_space() {
        while (pos_ < data_.size() && is_space(data_[pos_])) {
            if (data_[pos_] == '\n') ++line_;
            ++pos_;
        }
    }
    // Next whitespace-separated token, or "" at the end of the data.
    std::string_view token() {
        skip_space();
        size_t b = pos_;
        while (pos_ < data_.size() && !is_space(data_[pos_])) ++pos_;
        return data_.substr(b, pos_ - b);
    }
    std::string_view peek_token() {
        size_t p = pos_, l = line_;
        auto t = token();
        pos_ = p;
        line_ = l;
        return t;
    }
    std::string_view expect_token(const char* what) {
        auto t = token();
        if (t.empty()) fail(std::string("unexpected end of file, expected ") + what + " (file truncated?)");
        return t;
    }
    // Rest of the current line without its newline; consumes the newline.
    std::string_view rest_of_line() {
        size_t b = pos_;
        while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
        auto s = data_.substr(b, pos_ - b);
        if (pos_ < data_.size()) { ++pos_; ++line_; }
        if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
        return s;
    }
    // Exactly n bytes; fails naming `what` when the data ends first.
    std::string_view bytes(size_t n, const char* what) {
        if (n > remaining())
            fail(std::string(what) + ": needs " + std::to_string(n) + " bytes but only " + std::to_string(remaining()) +
                 " remain (file truncated, or a count is wrong)");
        auto s = data_.substr(pos_, n);
        pos_ += n;
        return s;
    }
    void seek(size_t p) { pos_ = p < data_.size() ? p : data_.size(); }

    // A non-negative integer token no larger than `max`.
    uint64_t count(const char* what, uint64_t max = std::numeric_limits<uint32_t>::max()) {
        auto t = expect_token(what);
        int64_t v = 0;
        if (!parse_number(t, v)) fail(std::string("expected ") + what + ", got '" + std::string(t) + "'");
        if (v < 0) fail(std::string(what) + " is negative (" + std::string(t) + ")");
        if (uint64_t(v) > max)
            fail(std::string(what) + " " + std::string(t) + " is larger than the supported " + std::to_string(max));
        return uint64_t(v);
    }

private:
    std::string_view data_;
    std::string file_;
    size_t pos_ = 0;
    size_t line_ = 1;
    bool text_ = true;
};

}  // namespace pathlet::io
