#include "text_raster.hpp"

#include <pathlet/pass.hpp>

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace overlay {

struct TextRaster::Impl {
    FT_Library lib = nullptr;
    FT_Face face = nullptr;
};

std::string default_font() {
    const std::string shipped = (std::filesystem::path(pathlet::share_dir()) / "fonts" / "DejaVuSans.ttf").string();
    for (const std::string& f : {shipped, std::string("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"),
                                 std::string("/usr/share/fonts/dejavu/DejaVuSans.ttf")})
        if (std::filesystem::exists(f)) return f;
    return shipped;  // the warning names the place the font is expected
}

void check_font_file(const std::string& path) {
    // A graph names the font (overlay.font): only a font file may be opened, never an arbitrary
    // file the graph points at (/etc/passwd, a key). By name first, without opening anything.
    const std::string ext = std::filesystem::path(path).extension().string();
    std::string lower;
    for (char c : ext) lower += char(std::tolower(static_cast<unsigned char>(c)));
    const std::string allowed = "allowed: regular TrueType/OpenType files named .ttf, .otf or .ttc";
    if (lower != ".ttf" && lower != ".otf" && lower != ".ttc")
        throw std::runtime_error("font '" + path + "' refused: not a font file name (" + allowed + ")");
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::status(path, ec);
    if (st.type() == std::filesystem::file_type::not_found) throw std::runtime_error("font '" + path + "' not found");
    if (ec) throw std::runtime_error("font '" + path + "' cannot be read: " + ec.message());
    if (st.type() != std::filesystem::file_type::regular)
        throw std::runtime_error("font '" + path + "' refused: not a regular file (" + allowed + ")");
    // Then its first four bytes: the sfnt versions of TrueType and OpenType, or a collection.
    char magic[4] = {};
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("font '" + path + "' cannot be read: " + std::strerror(errno));
    in.read(magic, 4);
    const std::string m(magic, 4);
    if (m != std::string("\0\1\0\0", 4) && m != "true" && m != "typ1" && m != "OTTO" && m != "ttcf")
        throw std::runtime_error("font '" + path + "' refused: its content is not a TrueType/OpenType font (" + allowed + ")");
}

TextRaster::TextRaster(const std::string& font_file, int pixel_size) : impl_(new Impl), size_(pixel_size) {
    check_font_file(font_file);
    if (FT_Init_FreeType(&impl_->lib)) throw std::runtime_error("FreeType could not start");
    if (FT_New_Face(impl_->lib, font_file.c_str(), 0, &impl_->face)) {
        FT_Done_FreeType(impl_->lib);
        impl_->lib = nullptr;
        throw std::runtime_error("font '" + font_file +
                                 "' could not be opened as a font (install fonts-dejavu-core, or set overlay.font)");
    }
    FT_Set_Pixel_Sizes(impl_->face, 0, FT_UInt(std::max(pixel_size, 1)));
}

TextRaster::TextRaster(int pixel_size) : size_(pixel_size) {}

TextRaster::~TextRaster() {
    if (!impl_) return;
    if (impl_->face) FT_Done_Face(impl_->face);
    if (impl_->lib) FT_Done_FreeType(impl_->lib);
}

const TextRaster::Glyph& TextRaster::glyph(uint32_t cp) const {
    auto it = cache_.find(cp);
    if (it != cache_.end()) return it->second;
    Glyph g;
    FT_Face face = impl_->face;
    if (FT_Load_Char(face, cp, FT_LOAD_RENDER) == 0) {
        const FT_Bitmap& b = face->glyph->bitmap;
        g.width = int(b.width);
        g.rows = int(b.rows);
        g.left = face->glyph->bitmap_left;
        g.top = face->glyph->bitmap_top;
        g.advance = int(face->glyph->advance.x >> 6);
        g.pixels.resize(size_t(g.width) * size_t(g.rows));
        for (int y = 0; y < g.rows; ++y)
            for (int x = 0; x < g.width; ++x) g.pixels[size_t(y * g.width + x)] = b.buffer[y * b.pitch + x];
    }
    return cache_.emplace(cp, std::move(g)).first->second;
}

namespace {
// UTF-8 to code points; a broken sequence becomes '?'.
std::vector<uint32_t> decode(const std::string& s) {
    std::vector<uint32_t> out;
    for (size_t i = 0; i < s.size();) {
        const unsigned char c = static_cast<unsigned char>(s[i]);
        int n = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : -1;
        if (n < 0 || (n > 0 && i + size_t(n) >= s.size())) {
            out.push_back('?');
            ++i;
            continue;
        }
        uint32_t cp = n == 0 ? c : (c & (0x3Fu >> n));
        for (int k = 1; k <= n; ++k) cp = (cp << 6) | (static_cast<unsigned char>(s[i + size_t(k)]) & 0x3Fu);
        out.push_back(cp);
        i += size_t(n) + 1;
    }
    return out;
}
}  // namespace

TextBitmap TextRaster::render(const std::string& utf8) const {
    if (!impl_) return render_builtin(utf8, size_);
    const std::vector<uint32_t> cps = decode(utf8);
    FT_Face face = impl_->face;
    TextBitmap t;
    t.ascent = int(face->size->metrics.ascender >> 6);
    t.height = std::max(1, int((face->size->metrics.ascender - face->size->metrics.descender) >> 6));
    int width = 0;
    for (uint32_t cp : cps) width += glyph(cp).advance;
    t.width = std::max(width, 1);
    t.coverage.assign(size_t(t.width) * size_t(t.height), 0);
    int pen = 0;
    for (uint32_t cp : cps) {
        const Glyph& g = glyph(cp);
        for (int y = 0; y < g.rows; ++y)
            for (int x = 0; x < g.width; ++x) {
                const int px = pen + g.left + x, py = t.ascent - g.top + y;
                if (px < 0 || py < 0 || px >= t.width || py >= t.height) continue;
                uint8_t& dst = t.coverage[size_t(py * t.width + px)];
                dst = std::max(dst, g.pixels[size_t(y * g.width + x)]);
            }
        pen += g.advance;
    }
    return t;
}

}  // namespace overlay
