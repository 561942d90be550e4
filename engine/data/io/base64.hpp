// Base64 as VTK uses it: encoding, and an incremental decoder that skips whitespace and
// accepts padding in the middle of the stream (VTK and others encode a header and its
// data either as one stream or as separately padded chunks; decoding the concatenation
// yields the same bytes either way).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace pathlet::io {

std::string base64_encode(std::string_view bytes);

class Base64Reader {
public:
    explicit Base64Reader(std::string_view text, size_t start = 0) : text_(text), pos_(start) {}
    // Appends exactly n decoded bytes to out; false (out partially filled) when the text
    // ends first or holds a character outside the alphabet (see error()).
    bool read(size_t n, std::string& out);
    bool read_to_end(std::string& out);  // everything left; false on a bad character
    // Upper bound on the bytes still decodable (checked before allocating).
    size_t max_remaining() const { return (text_.size() - pos_) / 4 * 3 + 3; }
    size_t pos() const { return pos_; }  // character position in text
    const char* error() const { return err_; }

private:
    std::string_view text_;
    size_t pos_;
    unsigned char pending_[3];
    size_t npending_ = 0, ipending_ = 0;
    const char* err_ = "";
    bool next_quantum();
};

// Decodes all of `text`; false on a bad character.
bool base64_decode(std::string_view text, std::string& out);

}  // namespace pathlet::io
