// Texture format names used by graph files and pin declarations, mapped onto GL sized
// internal formats. Pure data (enums only, no GL calls), so the graph compiler needs no context.
#pragma once

#include <pathlet/gl.hpp>

#include <string>
#include <vector>

namespace pathlet {

struct FormatInfo {
    const char* name;
    GLenum internal_format, pixel_format, pixel_type;  // the last two: for uploads/readbacks
    int bytes_per_pixel, channels;
    bool depth, is_float, is_integer;
};

const FormatInfo* find_format(const std::string& name);  // nullptr when unknown
const FormatInfo* find_format(GLenum internal_format);
std::vector<std::string> format_names();                 // in table order

}  // namespace pathlet
