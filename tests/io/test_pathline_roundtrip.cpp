// Write every PathlineFormat (and every internal writer variant), read it back, compare
// bit-exactly: binary formats store float32 verbatim, ASCII uses %.9g (round-trips float).
#include "io/pathline_formats.hpp"
#include "io/pathline_io.hpp"
#include "io_test_util.hpp"

#include <filesystem>

using namespace pathlet;
using namespace pathlet::io;

namespace {

struct Case { PathlineFormat fmt; const char* ext; const char* format_prefix; };

void PrintTo(const Case& c, std::ostream* os) { *os << c.format_prefix; }

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
    static const char* names[] = {"VtkAscii", "VtkBinary", "VtpAscii", "VtpBinary", "VtpAppendedRaw",
                                  "VtpAppendedBase64", "VtpZlib", "Native"};
    return names[int(info.param.fmt)];
}

class RoundTrip : public ::testing::TestWithParam<Case> {};

TEST_P(RoundTrip, WriteReadIsExact) {
    auto c = GetParam();
    Pathlines p = iotest::make_lines(40, 25);
    std::string path = iotest::temp_dir() + "/lines" + c.ext;
    save_pathlines(p, path, c.fmt);
    LoadReport r;
    Pathlines q = load_pathlines(path, {}, &r);
    iotest::expect_same(p, q);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    EXPECT_EQ(r.format.rfind(c.format_prefix, 0), 0u) << r.format;
}

INSTANTIATE_TEST_SUITE_P(Io, RoundTrip,
                         ::testing::Values(Case{PathlineFormat::VtkAscii, ".vtk", "VTK legacy 4.2 ASCII"},
                                           Case{PathlineFormat::VtkBinary, ".vtk", "VTK legacy 4.2 BINARY"},
                                           Case{PathlineFormat::VtpAscii, ".vtp", "VTK XML PolyData 1.0, ascii"},
                                           Case{PathlineFormat::VtpBinary, ".vtp", "VTK XML PolyData 1.0, binary"},
                                           Case{PathlineFormat::VtpAppendedRaw, ".vtp", "VTK XML PolyData 1.0, appended raw"},
                                           Case{PathlineFormat::VtpAppendedBase64, ".vtp", "VTK XML PolyData 1.0, appended base64"},
                                           Case{PathlineFormat::VtpZlib, ".vtp", "VTK XML PolyData 1.0, binary, zlib"},
                                           Case{PathlineFormat::Native, ".pathlet", "pathlet native cache v1"}),
                         case_name);

TEST(IoRoundTrip, NoExtensionIsSniffed) {
    Pathlines p = iotest::make_lines(3, 10);
    std::string dir = iotest::temp_dir();
    for (auto fmt : {PathlineFormat::VtkBinary, PathlineFormat::VtpAppendedRaw, PathlineFormat::Native}) {
        save_pathlines(p, dir + "/noext", fmt);
        iotest::expect_same(p, load_pathlines(dir + "/noext"));
    }
}

TEST(IoRoundTrip, LegacyVersion51BothEncodings) {
    Pathlines p = iotest::make_lines(7, 12);
    std::string dir = iotest::temp_dir();
    for (bool binary : {false, true}) {
        iotest::write_bytes(dir + "/a.vtk", write_vtk_legacy(p, {binary, true}));
        LoadReport r;
        iotest::expect_same(p, load_pathlines(dir + "/a.vtk", {}, &r));
        EXPECT_EQ(r.format, binary ? "VTK legacy 5.1 BINARY" : "VTK legacy 5.1 ASCII");
    }
}

// Every VTP variant: encodings x zlib x header width x byte order x chunking x pieces.
TEST(IoRoundTrip, VtpAllVariants) {
    Pathlines p = iotest::make_lines(9, 30);
    std::string dir = iotest::temp_dir();
    using E = VtpWriteOptions::Encoding;
    int n = 0;
    for (E e : {E::Ascii, E::Inline, E::AppendedRaw, E::AppendedBase64})
        for (bool zlib : {false, true})
            for (bool h64 : {false, true})
                for (bool be : {false, true})
                    for (bool sep : {false, true})
                        for (int pieces : {1, 3}) {
                            if (e == E::Ascii && (zlib || h64 || sep)) continue;
                            VtpWriteOptions o;
                            o.encoding = e;
                            o.zlib = zlib;
                            o.header64 = h64;
                            o.big_endian = be;
                            o.separate_header_chunk = sep;
                            o.pieces = pieces;
                            o.block_size = 1000;  // several blocks, last one partial
                            SCOPED_TRACE("variant " + std::to_string(n++));
                            iotest::write_bytes(dir + "/v.vtp", write_vtp(p, o));
                            iotest::expect_same(p, load_pathlines(dir + "/v.vtp"));
                        }
}

TEST(IoRoundTrip, FormatFromExtension) {
    EXPECT_EQ(format_from_extension("a/b.VTK"), PathlineFormat::VtkBinary);
    EXPECT_EQ(format_from_extension("b.vtp"), PathlineFormat::VtpZlib);
    EXPECT_EQ(format_from_extension("b.pathlet"), PathlineFormat::Native);
    EXPECT_THROW(format_from_extension("b.txt"), DataError);
}

TEST(IoRoundTrip, EmptyPathlinesRoundTripWithWarning) {
    Pathlines empty;
    std::string dir = iotest::temp_dir();
    for (auto [fmt, ext] : {std::pair{PathlineFormat::VtkBinary, ".vtk"}, {PathlineFormat::VtpZlib, ".vtp"},
                            {PathlineFormat::Native, ".pathlet"}, {PathlineFormat::VtpAppendedRaw, ".vtp"}}) {
        std::string path = dir + "/empty" + ext;
        save_pathlines(empty, path, fmt);
        LoadReport r;
        Pathlines q = load_pathlines(path, {}, &r);
        EXPECT_TRUE(q.empty());
        ASSERT_FALSE(r.warnings.empty()) << ext;
        EXPECT_NE(r.warnings.back().find("empty"), std::string::npos);
    }
}

TEST(IoRoundTrip, SaveIsAtomicAndRejectsInconsistentInput) {
    Pathlines p = iotest::make_lines(2, 5);
    p.time.pop_back();
    std::string path = iotest::temp_dir() + "/bad.pathlet";
    EXPECT_THROW(save_pathlines(p, path, PathlineFormat::Native), DataError);
    EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
