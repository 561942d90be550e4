#include "formats.hpp"

namespace pathlet {

namespace {

// Bytes per pixel are what the driver is likely to allocate (depth24 is padded to 4 bytes);
// they feed the memory estimate, not uploads of packed formats.
constexpr FormatInfo kFormats[] = {
    {"r8", GL_R8, GL_RED, GL_UNSIGNED_BYTE, 1, 1, false, false, false},
    {"rg8", GL_RG8, GL_RG, GL_UNSIGNED_BYTE, 2, 2, false, false, false},
    {"rgba8", GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 4, 4, false, false, false},
    {"rgba8_srgb", GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE, 4, 4, false, false, false},
    {"r16f", GL_R16F, GL_RED, GL_HALF_FLOAT, 2, 1, false, true, false},
    {"rg16f", GL_RG16F, GL_RG, GL_HALF_FLOAT, 4, 2, false, true, false},
    {"rgba16f", GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT, 8, 4, false, true, false},
    {"r32f", GL_R32F, GL_RED, GL_FLOAT, 4, 1, false, true, false},
    {"rg32f", GL_RG32F, GL_RG, GL_FLOAT, 8, 2, false, true, false},
    {"rgba32f", GL_RGBA32F, GL_RGBA, GL_FLOAT, 16, 4, false, true, false},
    {"r32ui", GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, 4, 1, false, false, true},
    {"rg32ui", GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT, 8, 2, false, false, true},
    {"rgba32ui", GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT, 16, 4, false, false, true},
    {"r32i", GL_R32I, GL_RED_INTEGER, GL_INT, 4, 1, false, false, true},
    {"rgb10a2", GL_RGB10_A2, GL_RGBA, GL_UNSIGNED_INT_2_10_10_10_REV, 4, 4, false, false, false},
    {"r11g11b10f", GL_R11F_G11F_B10F, GL_RGB, GL_UNSIGNED_INT_10F_11F_11F_REV, 4, 3, false, true, false},
    {"depth16", GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT, 2, 1, true, false, false},
    {"depth24", GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, 4, 1, true, false, false},
    {"depth32f", GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, 4, 1, true, true, false},
    {"depth24_stencil8", GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8, 4, 2, true, false, false},
};

}  // namespace

const FormatInfo* find_format(const std::string& name) {
    for (const auto& f : kFormats)
        if (name == f.name) return &f;
    return nullptr;
}

const FormatInfo* find_format(GLenum internal_format) {
    for (const auto& f : kFormats)
        if (f.internal_format == internal_format) return &f;
    return nullptr;
}

std::vector<std::string> format_names() {
    std::vector<std::string> v;
    for (const auto& f : kFormats) v.push_back(f.name);
    return v;
}

}  // namespace pathlet
