// Image files in a build without OpenImageIO: PNG written and read through stb. Every other
// format is refused with the file and the reason; EXR and TIFF in particular, which keep floats.
// Same contract as the OpenImageIO backend (image_io.hpp): values unchanged, 8-bit output by
// to_unorm8, a temporary name renamed into place.
#include "image_io_stb.hpp"

#include "io/file_bytes.hpp"
#include "util/atomic_file.hpp"

#include <pathlet_build_features.hpp>

#include <algorithm>
#include <climits>
#include <stdexcept>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#include <stb/stb_image.h>

namespace pathlet::stb {

namespace {

// Why a file that is not a PNG cannot be written or read here.
std::string not_in_this_build(const std::string& ext) {
    const bool floats = ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff";
    return (floats ? "this build has no " + (ext == ".exr" ? std::string("EXR") : ext.substr(1))
                   : std::string("this build reads and writes PNG only")) +
           " (built without OpenImageIO: PATHLET_WITH_OPENIMAGEIO=OFF, as the lean bundle is); use a .png name, or "
           "the full build (the default bundle)";
}

void append(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

template <class T>
void to_floats(const T* p, float scale, Image& img) {
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float(p[i]) / scale;
}

}  // namespace

void write_png(const std::string& path, const Image& img) {
    check_image_shape(img, path);
    const std::string ext = io::lower_extension(path);
    if (!ext.empty() && ext != ".png") throw std::runtime_error(path + ": cannot write image: " + not_in_this_build(ext));
    std::vector<uint8_t> bytes(img.pixels.size());
    std::transform(img.pixels.begin(), img.pixels.end(), bytes.begin(), to_unorm8);
    std::string png;
    static const bool level_set = (stbi_write_png_compression_level = kPngCompressionLevel,  // once: globals
                                   stbi_write_force_png_filter = kPngFilterUp, true);
    (void)level_set;
    if (!stbi_write_png_to_func(append, &png, img.width, img.height, img.channels, bytes.data(), img.width * img.channels))
        throw std::runtime_error(path + ": cannot write image: PNG encoding failed");
    write_file_atomic(path, png);  // a temporary name, then renamed
}

Image read_png(const std::string& path) {
    const std::string ext = io::lower_extension(path);
    if (ext != ".png") throw std::runtime_error(path + ": cannot read image: " + not_in_this_build(ext));
    const std::string bytes = io::read_file_bytes(path);
    if (bytes.size() > size_t(INT_MAX)) throw std::runtime_error(path + ": cannot read image: larger than 2 GiB");
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int len = int(bytes.size());
    Image img;
    if (!stbi_info_from_memory(data, len, &img.width, &img.height, &img.channels))
        throw std::runtime_error(path + ": cannot read image: " + stbi_failure_reason());
    img.pixels.resize(size_t(img.width) * size_t(img.height) * size_t(img.channels));
    int w = 0, h = 0, c = 0;
    const bool wide = stbi_is_16_bit_from_memory(data, len);
    void* p = wide ? static_cast<void*>(stbi_load_16_from_memory(data, len, &w, &h, &c, 0))
                   : static_cast<void*>(stbi_load_from_memory(data, len, &w, &h, &c, 0));
    if (!p) throw std::runtime_error(path + ": cannot read image: " + stbi_failure_reason());
    if (wide)
        to_floats(static_cast<const stbi_us*>(p), 65535.0f, img);
    else
        to_floats(static_cast<const stbi_uc*>(p), 255.0f, img);
    stbi_image_free(p);
    return img;
}

}  // namespace pathlet::stb

#if !PATHLET_WITH_OPENIMAGEIO
namespace pathlet {
void write_image(const std::string& path, const Image& img) { stb::write_png(path, img); }
Image read_image(const std::string& path) { return stb::read_png(path); }
}  // namespace pathlet
#endif
