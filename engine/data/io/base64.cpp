#include "base64.hpp"

#include <array>

namespace pathlet::io {

static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

static const std::array<signed char, 256> kDecode = [] {
    std::array<signed char, 256> t{};
    t.fill(-1);
    for (int i = 0; i < 64; ++i) t[(unsigned char)kAlphabet[i]] = (signed char)i;
    t['='] = -2;
    for (unsigned char c : {' ', '\n', '\r', '\t', '\f', '\v'}) t[c] = -3;
    return t;
}();

std::string base64_encode(std::string_view in) {
    std::string out;
    out.reserve((in.size() + 2) / 3 * 4);
    size_t i = 0;
    const auto* s = reinterpret_cast<const unsigned char*>(in.data());
    for (; i + 3 <= in.size(); i += 3) {
        uint32_t v = (s[i] << 16) | (s[i + 1] << 8) | s[i + 2];
        out += kAlphabet[v >> 18];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += kAlphabet[v & 63];
    }
    if (size_t r = in.size() - i) {
        uint32_t v = s[i] << 16 | (r == 2 ? s[i + 1] << 8 : 0);
        out += kAlphabet[v >> 18];
        out += kAlphabet[(v >> 12) & 63];
        out += r == 2 ? kAlphabet[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

// Decodes the next 4-character quantum into pending_ (1 to 3 bytes).
bool Base64Reader::next_quantum() {
    int vals[4];
    int n = 0, pad = 0;
    while (n + pad < 4) {
        if (pos_ >= text_.size()) {
            if (n + pad == 0) err_ = "base64 data ended early";
            else err_ = "base64 data ended inside a quantum";
            return false;
        }
        signed char d = kDecode[(unsigned char)text_[pos_++]];
        if (d == -3) continue;
        if (d == -1) { err_ = "character outside the base64 alphabet"; return false; }
        if (d == -2) { ++pad; continue; }
        if (pad) { err_ = "base64 padding in the middle of a quantum"; return false; }
        vals[n++] = d;
    }
    if (n < 2) { err_ = "base64 quantum with too much padding"; return false; }
    uint32_t v = (vals[0] << 18) | (vals[1] << 12) | (n > 2 ? vals[2] << 6 : 0) | (n > 3 ? vals[3] : 0);
    pending_[0] = (unsigned char)(v >> 16);
    pending_[1] = (unsigned char)(v >> 8);
    pending_[2] = (unsigned char)v;
    npending_ = size_t(n - 1);
    ipending_ = 0;
    return true;
}

bool Base64Reader::read(size_t n, std::string& out) {
    out.reserve(out.size() + n);
    while (n > 0) {
        if (ipending_ == npending_ && !next_quantum()) return false;
        size_t k = std::min(n, npending_ - ipending_);
        out.append(reinterpret_cast<const char*>(pending_) + ipending_, k);
        ipending_ += k;
        n -= k;
    }
    return true;
}

bool Base64Reader::read_to_end(std::string& out) {
    out.append(ipending_ < npending_ ? reinterpret_cast<const char*>(pending_) + ipending_ : "", npending_ - ipending_);
    ipending_ = npending_;
    while (true) {
        while (pos_ < text_.size() && kDecode[(unsigned char)text_[pos_]] == -3) ++pos_;
        if (pos_ >= text_.size()) return true;
        if (!next_quantum()) return false;
        out.append(reinterpret_cast<const char*>(pending_), npending_);
        ipending_ = npending_;
    }
}

bool base64_decode(std::string_view text, std::string& out) {
    out.reserve(out.size() + text.size() / 4 * 3);
    return Base64Reader(text).read_to_end(out);
}

}  // namespace pathlet::io
