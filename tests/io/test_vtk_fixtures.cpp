// Hand-written fixtures in the exact shapes VTK 9.1 writes (the python
// vtkmodules generator was not available on this machine): 5.1 OFFSETS layout with
// FIELD arrays and METADATA blocks, 4.2 with every skippable section, VTP inline base64
// with an <InformationKey> child, and zlib with nBlocks = 0.
#include "io/base64.hpp"
#include "io/pathline_io.hpp"
#include "io/zlib_blocks.hpp"
#include "io_test_util.hpp"

using namespace pathlet;
using namespace pathlet::io;

namespace {

std::string fixture(const char* name) { return std::string(PATHLET_TEST_SOURCE_DIR) + "/fixtures/" + name; }

// The two lines every fixture holds: 3 + 4 points, time 0.01 s apart, velocity as written.
void expect_fixture_lines(const Pathlines& p) {
    ASSERT_EQ(p.line_count(), 2u);
    ASSERT_EQ(p.point_count(), 7u);
    EXPECT_EQ(p.lines[0].count, 3u);
    EXPECT_EQ(p.lines[1].count, 4u);
    EXPECT_EQ(p.position[4], glm::vec3(1, 1, 0.25f));
    EXPECT_FLOAT_EQ(p.time[2], 0.02f);
    EXPECT_FLOAT_EQ(p.time[6], 0.03f);
    EXPECT_EQ(p.velocity[5], glm::vec3(100, 50, 50));
}

TEST(IoFixtures, Legacy51AsciiWithFieldAndMetadata) {
    LoadReport r;
    Pathlines p = load_pathlines(fixture("vtk9_51_ascii_field.vtk"), {}, &r);
    expect_fixture_lines(p);
    EXPECT_EQ(r.format, "VTK legacy 5.1 ASCII");
    EXPECT_EQ(r.arrays, (std::vector<std::string>{"time (1 comp)", "velocity (3 comp)"}));
    EXPECT_TRUE(r.warnings.empty());
}

TEST(IoFixtures, Legacy42AsciiSkipsOtherSectionsCaseInsensitive) {
    LoadReport r;
    Pathlines p = load_pathlines(fixture("vtk42_ascii_mixed.vtk"), {}, &r);
    expect_fixture_lines(p);  // IntegrationTime and U found automatically
    EXPECT_EQ(r.arrays, (std::vector<std::string>{"IntegrationTime (1 comp)", "U (3 comp)"}));
}

TEST(IoFixtures, VtpInlineBase64WithInformationKey) {
    LoadReport r;
    Pathlines p = load_pathlines(fixture("vtk9_inline_uint32.vtp"), {}, &r);
    expect_fixture_lines(p);
    EXPECT_NE(r.format.find("UInt32"), std::string::npos) << r.format;
}

TEST(IoFixtures, ChosenArraysByName) {
    LoadOptions o;
    o.time_array = "integrationtime";  // case-insensitive
    o.velocity_array = "U";
    expect_fixture_lines(load_pathlines(fixture("vtk42_ascii_mixed.vtk"), o));
    o.time_array = "nope";
    try {
        load_pathlines(fixture("vtk42_ascii_mixed.vtk"), o);
        FAIL();
    } catch (const DataError& e) {
        EXPECT_NE(std::string(e.what()).find("no point array named 'nope'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("IntegrationTime, U"), std::string::npos) << e.what();
    }
}

TEST(IoFixtures, ZlibZeroLengthArrayHeader) {
    // (0, 32768, 0): no blocks at all, as VTK writes for empty arrays.
    std::string h;
    base64_decode("AAAAAACAAAAAAAAA", h);
    ASSERT_EQ(h.size(), 12u);
    std::string empty = "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt32\" "
                        "compressor=\"vtkZLibDataCompressor\"><PolyData><Piece NumberOfPoints=\"0\" NumberOfLines=\"0\">"
                        "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">AAAAAACAAAAAAAAA"
                        "</DataArray></Points></Piece></PolyData></VTKFile>";
    std::string path = iotest::temp_dir() + "/empty.vtp";
    iotest::write_bytes(path, empty);
    LoadReport r;
    EXPECT_TRUE(load_pathlines(path, {}, &r).empty());
    ASSERT_FALSE(r.warnings.empty());
    // And the codec agrees with VTK's documented header example (1, 32768, 84, 26).
    std::string hdr;
    base64_decode("AQAAAACAAABUAAAAGgAAAA==", hdr);
    EXPECT_EQ(hdr, zlib_blocks_encode_header({1, 32768, 84, {26}}, 4, false));
}

TEST(IoFixtures, Base64SeparateAndJointChunksDecodeAlike) {
    std::string data(4, '\0');
    data[0] = 28;
    data += "hello world, 28 bytes long!!";
    std::string joint, separate;
    ASSERT_TRUE(base64_decode(base64_encode(data), joint));
    ASSERT_TRUE(base64_decode(base64_encode(data.substr(0, 4)) + "\n  " + base64_encode(data.substr(4)), separate));
    EXPECT_EQ(joint, data);
    EXPECT_EQ(separate, data);
}

}  // namespace
