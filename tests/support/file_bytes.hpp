#pragma once
// Two writes of the same frame compared as files: byte for byte, but for an EXR's "capDate" (the
// second it was written). An EXR whose bytes still differ must hold the same pixels bit for bit:
// in one process, two writes of equal pixels now and then come out with other bytes (seen in the
// capture and async-output tests under load, never across processes; the writer library's
// encoding, not the pixels), and a note says where.
#include "image_io.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace pathlet {

inline std::string frame_file_bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::string b{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const std::string key("capDate\0string\0", 15);
    if (const size_t at = b.find(key); at != std::string::npos && at + key.size() + 4 <= b.size()) {
        uint32_t n = 0;
        std::memcpy(&n, &b[at + key.size()], 4);
        if (at + key.size() + 4 + n <= b.size()) b.replace(at + key.size() + 4, n, n, '#');
    }
    return b;
}

inline void expect_same_frame_file(const std::filesystem::path& mine, const std::filesystem::path& theirs) {
    const std::string a = frame_file_bytes(mine), b = frame_file_bytes(theirs);
    const Image back = read_image(mine.string()), expected = read_image(theirs.string());
    if (mine.extension() != ".exr") {
        EXPECT_TRUE(a == b) << mine << " differs from " << theirs;
    } else if (a != b) {
        size_t at = 0;
        while (at < std::min(a.size(), b.size()) && a[at] == b[at]) ++at;
        std::printf("note: %s differs from %s from byte %zu (sizes %zu, %zu); its pixels are compared\n",
                    mine.c_str(), theirs.c_str(), at, a.size(), b.size());
    }
    EXPECT_EQ(back.width, expected.width) << mine;
    EXPECT_EQ(back.height, expected.height) << mine;
    EXPECT_EQ(back.channels, expected.channels) << mine;
    EXPECT_EQ(back.is_float, expected.is_float) << mine;
    ASSERT_EQ(back.pixels.size(), expected.pixels.size()) << mine;
    EXPECT_EQ(std::memcmp(back.pixels.data(), expected.pixels.data(), back.pixels.size() * sizeof(float)), 0) << mine;
}

}  // namespace pathlet
