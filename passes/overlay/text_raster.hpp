// Text to coverage bitmaps: FreeType with a font file (one face, one pixel size, glyphs cached),
// or the built-in stroke font (builtin_font.cpp) when there is no usable font file.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace overlay {

struct TextBitmap {
    int width = 0, height = 0;  // height = the face's line height; baseline at `ascent`
    int ascent = 0;
    std::vector<uint8_t> coverage;  // row 0 at the top, width * height
};

// Throws std::runtime_error unless `path` is a regular .ttf, .otf or .ttc file that starts like
// a TrueType/OpenType font: the check before a font a graph names is opened. The message says
// which: not a font file name, not found, not a regular file, cannot be read, not a font.
void check_font_file(const std::string& path);

class TextRaster {
public:
    // Throws std::runtime_error naming the font file when it is refused (check_font_file) or
    // cannot be opened as a font.
    TextRaster(const std::string& font_file, int pixel_size);
    // The built-in font (no file: stb_easy_font's ASCII strokes, anti-aliased by area).
    explicit TextRaster(int pixel_size);
    ~TextRaster();
    TextRaster(const TextRaster&) = delete;
    TextRaster& operator=(const TextRaster&) = delete;

    TextBitmap render(const std::string& utf8) const;
    int pixel_size() const { return size_; }
    bool builtin() const { return impl_ == nullptr; }

private:
    struct Glyph {
        int width = 0, rows = 0, left = 0, top = 0, advance = 0;
        std::vector<uint8_t> pixels;
    };
    const Glyph& glyph(uint32_t codepoint) const;

    struct Impl;
    std::unique_ptr<Impl> impl_;  // null: the built-in font
    int size_ = 0;
    mutable std::map<uint32_t, Glyph> cache_;
};

// The built-in font's bitmap of `text` at `pixel_size` (line height); characters outside
// printable ASCII are drawn as '?'.
TextBitmap render_builtin(const std::string& text, int pixel_size);

// The default font: DejaVu Sans in the share folder's fonts/ (build tree, install, bundle), else
// Debian's fonts-dejavu-core; when neither is there, the share folder's path (the warning names it).
std::string default_font();

}  // namespace overlay
