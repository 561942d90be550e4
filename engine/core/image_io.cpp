#include "image_io.hpp"
#include "pixel_store.hpp"

#include "util/atomic_file.hpp"

#include <pathlet_build_features.hpp>

#if PATHLET_WITH_OPENIMAGEIO  // else PNG through stb: image_io_stb.cpp
#include <OpenImageIO/imageio.h>
#endif

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace pathlet {

void check_image_shape(const Image& img, const std::string& path) {
    if (img.width <= 0 || img.height <= 0 || img.channels < 1 || img.channels > 4 ||
        img.pixels.size() != size_t(img.width) * size_t(img.height) * size_t(img.channels))
        throw std::runtime_error(path + ": cannot write image: inconsistent image (" + std::to_string(img.width) +
                                 "x" + std::to_string(img.height) + "x" + std::to_string(img.channels) + ", " +
                                 std::to_string(img.pixels.size()) + " values)");
}

namespace {

#if PATHLET_WITH_OPENIMAGEIO
std::string lower_extension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

bool keeps_float(const std::string& ext, const Image& img) {
    return ext == ".exr" || ext == ".hdr" || ((ext == ".tif" || ext == ".tiff") && img.is_float);
}

// Drops alpha (for JPEG and friends); returns values in the layout that is written.
std::vector<float> select_channels(const Image& img, int channels) {
    std::vector<float> out;
    out.reserve(size_t(img.width) * size_t(img.height) * size_t(channels));
    for (size_t i = 0; i < img.pixels.size(); i += size_t(img.channels))
        out.insert(out.end(), img.pixels.begin() + long(i), img.pixels.begin() + long(i) + channels);
    return out;
}
#endif

GLenum gl_format_for(int channels) {
    switch (channels) {
        case 1: return GL_RED;
        case 2: return GL_RG;
        case 3: return GL_RGB;
        case 4: return GL_RGBA;
    }
    throw std::invalid_argument("read_texture: channels must be 1..4, not " + std::to_string(channels));
}

}  // namespace

std::vector<uint8_t> to_rgba8(const Image& img) {
    const size_t n = size_t(img.width) * size_t(img.height);
    std::vector<uint8_t> out(n * 4, 255);
    const size_t c = size_t(img.channels);
    for (size_t i = 0; i < n; ++i) {
        const float* p = &img.pixels[i * c];
        for (size_t k = 0; k < 3; ++k) out[i * 4 + k] = to_unorm8(c >= 3 ? p[k] : p[0]);  // grey replicated
        if (c == 2 || c == 4) out[i * 4 + 3] = to_unorm8(p[c - 1]);
    }
    return out;
}

#if PATHLET_WITH_OPENIMAGEIO
void write_image(const std::string& path, const Image& img) {
    check_image_shape(img, path);
    const std::string ext = lower_extension(path);
    auto out = ext.empty() ? OIIO::ImageOutput::create("png") : OIIO::ImageOutput::create(path);
    if (!out) throw std::runtime_error(path + ": cannot write image: " + OIIO::geterror());

    int channels = img.channels;
    if (channels == 4 && !out->supports("alpha")) channels = 3;
    const bool as_float = keeps_float(ext, img);
    OIIO::ImageSpec spec(img.width, img.height, channels, as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // store the buffer's values, no (un)premultiplying
    spec.attribute("png:compressionLevel", kPngCompressionLevel);
    spec.attribute("png:filter", 0x08 << kPngFilterUp);  // libpng's PNG_FILTER_UP: that filter alone

    // The image's own floats where every channel is written (no copy of a frame on the writers' path).
    std::vector<float> selected;
    if (channels != img.channels) selected = select_channels(img, channels);
    const std::vector<float>& values = channels == img.channels ? img.pixels : selected;
    std::vector<uint8_t> bytes;
    if (!as_float) {  // our own rounding rule, not OIIO's, so every 8-bit path agrees
        bytes.resize(values.size());
        std::transform(values.begin(), values.end(), bytes.begin(), to_unorm8);
    }

    const std::string tmp = temp_path_for(path);
    auto fail = [&](const std::string& why) {
        std::error_code ec;
        fs::remove(tmp, ec);
        throw std::runtime_error(path + ": cannot write image: " + why);
    };
    if (!out->open(tmp, spec)) fail(out->geterror());
    bool ok = as_float ? out->write_image(OIIO::TypeDesc::FLOAT, values.data())
                       : out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
    if (!ok) {
        std::string why = out->geterror();
        out->close();
        fail(why);
    }
    if (!out->close()) fail(out->geterror());
    commit_temp(tmp, path);
}

Image read_image(const std::string& path) {
    // Values as stored: OIIO would otherwise premultiply PNG colour by alpha on read.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) throw std::runtime_error(path + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    Image img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels = std::min(spec.nchannels, 4);
    img.is_float = spec.format.is_floating_point();
    img.pixels.resize(size_t(img.width) * size_t(img.height) * size_t(img.channels));
    if (!in->read_image(0, 0, 0, img.channels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
        throw std::runtime_error(path + ": cannot read image: " + in->geterror());
    in->close();
    return img;
}
#endif

static Image read_texture_as(GLuint tex, int w, int h, int mip, int channels, GLenum format);

Image read_texture(GLuint tex, int w, int h, int mip, int channels) {
    // Depth textures can only be read as GL_DEPTH_COMPONENT: read one channel, then spread
    // it over the requested channels (grey, alpha 1) so captures of depth just work.
    GLint internal = 0;
    glGetTextureLevelParameteriv(tex, mip, GL_TEXTURE_INTERNAL_FORMAT, &internal);
    if (internal == GL_DEPTH_COMPONENT16 || internal == GL_DEPTH_COMPONENT24 || internal == GL_DEPTH_COMPONENT32F ||
        internal == GL_DEPTH_COMPONENT32) {
        Image d = read_texture_as(tex, w, h, mip, 1, GL_DEPTH_COMPONENT);
        if (channels == 1) return d;
        Image out;
        out.width = w, out.height = h, out.channels = channels, out.is_float = true;
        out.pixels.resize(size_t(w) * size_t(h) * size_t(channels));
        for (size_t i = 0; i < size_t(w) * size_t(h); ++i)
            for (int c = 0; c < channels; ++c) out.pixels[i * size_t(channels) + size_t(c)] = c == 3 ? 1.0f : d.pixels[i];
        return out;
    }
    return read_texture_as(tex, w, h, mip, channels, gl_format_for(channels));
}

static Image read_texture_as(GLuint tex, int w, int h, int mip, int channels, GLenum format) {
    GLint tw = 0, th = 0;
    glGetTextureLevelParameteriv(tex, mip, GL_TEXTURE_WIDTH, &tw);
    glGetTextureLevelParameteriv(tex, mip, GL_TEXTURE_HEIGHT, &th);
    if (tw != w || th != h)
        throw std::runtime_error("read_texture: texture " + std::to_string(tex) + " level " + std::to_string(mip) +
                                 " is " + std::to_string(tw) + "x" + std::to_string(th) + ", not " +
                                 std::to_string(w) + "x" + std::to_string(h));

    const size_t row = size_t(w) * size_t(channels);
    std::vector<float> bottom_up(row * size_t(h));
    GLenum err = GL_NO_ERROR;
    {
        const PlainPixelStore plain(PlainPixelStore::pack);
        while (glGetError() != GL_NO_ERROR) {}  // earlier errors are not ours (KHR_debug reports them)
        glGetTextureImage(tex, mip, format, GL_FLOAT, GLsizei(bottom_up.size() * sizeof(float)), bottom_up.data());
        err = glGetError();
    }
    if (err != GL_NO_ERROR) {
        char code[16];
        std::snprintf(code, sizeof code, "0x%04x", unsigned(err));
        throw std::runtime_error("read_texture: glGetTextureImage of texture " + std::to_string(tex) + " failed (GL error " +
                                 code + ")");
    }

    Image img;
    img.width = w;
    img.height = h;
    img.channels = channels;
    img.is_float = true;
    img.pixels.resize(bottom_up.size());
    for (int y = 0; y < h; ++y)
        std::copy_n(bottom_up.begin() + long(size_t(h - 1 - y) * row), row, img.pixels.begin() + long(size_t(y) * row));
    return img;
}

std::string expand_pattern(const std::string& pattern, const std::map<std::string, std::string>& vars,
                           uint64_t frame) {
    auto bad = [&](const std::string& why) {
        return std::invalid_argument("capture pattern '" + pattern + "': " + why);
    };
    std::string out;
    for (size_t i = 0; i < pattern.size(); ++i) {
        const char c = pattern[i];
        if ((c == '{' || c == '}') && i + 1 < pattern.size() && pattern[i + 1] == c) {
            out += c;
            ++i;
            continue;
        }
        if (c == '}') throw bad("unmatched '}' at " + std::to_string(i));
        if (c != '{') {
            out += c;
            continue;
        }
        const size_t close = pattern.find('}', i);
        if (close == std::string::npos) throw bad("unclosed '{' at " + std::to_string(i));
        const std::string field = pattern.substr(i + 1, close - i - 1);
        const size_t colon = field.find(':');
        const std::string name = field.substr(0, colon);
        const std::string spec = colon == std::string::npos ? "" : field.substr(colon + 1);
        if (name == "frame") {
            std::string digits = std::to_string(frame);
            if (!spec.empty()) {
                if (spec.size() > 3 || !std::all_of(spec.begin(), spec.end(), ::isdigit))
                    throw bad("'{" + field + "}': frame format must be 0N, as in {frame:05}");
                size_t width = std::stoul(spec);
                if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
            }
            out += digits;
        } else {
            auto it = vars.find(name);
            if (it == vars.end()) {
                std::string known = "frame";
                for (const auto& [k, v] : vars) known += ", " + k;
                throw bad("unknown name '{" + name + "}' (known: " + known + ")");
            }
            if (!spec.empty()) throw bad("'{" + field + "}': only {frame} takes a format");
            out += it->second;
        }
        i = close;
    }
    return out;
}

void ensure_parent_dir(const std::string& path) {
    const fs::path parent = fs::path(path).parent_path();
    if (parent.empty()) return;
    std::error_code ec;
    fs::create_directories(parent, ec);
    if (ec) throw std::runtime_error(path + ": cannot create directory " + parent.string() + ": " + ec.message());
}

Image box_downsample(const Image& img, int factor) {
    if (factor <= 1) return img;
    Image out;
    out.width = img.width / factor;
    out.height = img.height / factor;
    out.channels = img.channels;
    out.is_float = img.is_float;
    out.pixels.assign(size_t(out.width) * size_t(out.height) * size_t(out.channels), 0.0f);
    const bool weighted = img.channels == 4;
    const float n = float(factor * factor);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            float sum[4] = {0, 0, 0, 0};
            for (int j = 0; j < factor; ++j)
                for (int i = 0; i < factor; ++i) {
                    const int sx = x * factor + i, sy = y * factor + j;
                    const float w = weighted ? img.at(sx, sy, 3) : 1.0f;
                    for (int c = 0; c < img.channels; ++c)
                        sum[c] += (weighted && c < 3 ? w : 1.0f) * img.at(sx, sy, c);
                }
            for (int c = 0; c < out.channels; ++c) {
                float v = sum[c] / n;
                if (weighted && c < 3) {
                    // alpha-weighted mean; where every sample is transparent, the plain mean
                    float plain = 0.0f;
                    if (sum[3] <= 0.0f) {
                        for (int j = 0; j < factor; ++j)
                            for (int i = 0; i < factor; ++i) plain += img.at(x * factor + i, y * factor + j, c);
                        v = plain / n;
                    } else {
                        v = sum[c] / sum[3];
                    }
                }
                out.at(x, y, c) = v;
            }
        }
    return out;
}

}  // namespace pathlet
