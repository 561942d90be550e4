// Units of a data set: written and read back by every pathline writer (VTK field data,
// the native cache's units block), read from field data as VTK itself writes it, derived
// where they follow (velocity = length/time), given by --units, and never invented.
#include "io/base64.hpp"
#include "io/native_cache.hpp"
#include "io/pathline_formats.hpp"
#include "io/pathline_io.hpp"
#include "io/units.hpp"
#include "io_test_util.hpp"

#include <cstring>

using namespace pathlet;
using namespace pathlet::io;

namespace {

struct IoUnits : iotest::FileTest {
    static bool has(const LoadReport& r, const std::string& needle) { return iotest::reports(r, needle); }
};

const char* kLines =
    "POINTS 3 float\n0 0 0 1 0 0 2 0 0\nLINES 1 4\n3 0 1 2\nPOINT_DATA 3\nSCALARS time float\nLOOKUP_TABLE default\n0 1 2\n";

TEST_F(IoUnits, EveryWriterWritesThemAndEveryReaderReadsThemBack) {
    Pathlines p = iotest::make_lines(3, 6);
    p.units = {"mm", "s", "m s-1"};  // a space inside: VTK legacy ASCII escapes it as %20
    for (auto& [name, bytes] : iotest::every_writer(p)) {
        Pathlines q = load_pathlines(put(name, bytes));
        EXPECT_EQ(q.units, p.units) << name;
        iotest::expect_same(q, p);
    }
    EXPECT_NE(write_vtk_legacy(p, {false, false}).find("VelocityUnit 1 1 string\nm%20s-1\n"), std::string::npos);
    // Only the known ones are written; none at all means no field data and no units block.
    p.units = {"mm", "", ""};
    EXPECT_EQ(load_pathlines(put("d.vtp", write_vtp(p, {}))).units, (Units{"mm", "", ""}));
    p.units = {};
    EXPECT_EQ(write_vtp(p, {}).find("FieldData"), std::string::npos);
    EXPECT_EQ(write_vtk_legacy(p, {false, false}).find("FIELD"), std::string::npos);
    const std::string n = encode_native(p);
    uint64_t off = 1;
    std::memcpy(&off, n.data() + 72, 8);
    EXPECT_EQ(off, 0u);
    EXPECT_EQ(load_pathlines(put("e.pathlet", n)).units, Units{});
}

TEST_F(IoUnits, FieldDataAsVtkWritesIt) {
    // Legacy ASCII and BINARY (a length byte 0b11xxxxxx, then the characters).
    std::string head = "# vtk DataFile Version 4.2\nu\nASCII\nDATASET POLYDATA\n";
    std::string ascii = head + "FIELD FieldData 2\nLengthUnit 1 1 string\nmm\nTimeUnit 1 1 string\ns\n" + kLines;
    EXPECT_EQ(load_pathlines(put("a.vtk", ascii)).units, (Units{"mm", "s", "mm/s"}));  // velocity derived: mm/s
    // VTP: ascii character codes with a NUL after each string, and base64 bytes after a UInt32 size.
    auto vtp = [](const std::string& field) {
        return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
               "<PolyData>\n<FieldData>\n" + field + "</FieldData>\n"
               "<Piece NumberOfPoints=\"2\" NumberOfLines=\"1\">\n<PointData>\n"
               "<DataArray type=\"Float32\" Name=\"time\" format=\"ascii\">\n0 1\n</DataArray>\n</PointData>\n"
               "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">\n0 0 0 1 0 0\n</DataArray></Points>\n"
               "<Lines><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n0 1\n</DataArray>\n"
               "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n2\n</DataArray></Lines>\n</Piece>\n</PolyData>\n</VTKFile>\n";
    };
    const std::string sized("\x04\x00\x00\x00m/s\x00", 8);  // UInt32 size 4: VTK counts each string's NUL
    std::string field = "<DataArray type=\"String\" Name=\"LengthUnit\" NumberOfTuples=\"1\" format=\"ascii\">109 0</DataArray>\n"
                        "<DataArray type=\"String\" Name=\"VelocityUnit\" NumberOfTuples=\"1\" format=\"binary\">" +
                        base64_encode(sized) + "</DataArray>\n";
    EXPECT_EQ(load_pathlines(put("b.vtp", vtp(field))).units, (Units{"m", "", "m/s"}));
    // A unit we cannot show is dropped with a warning (control bytes), as is a numeric "unit".
    LoadReport r;
    std::string bad = "<DataArray type=\"String\" Name=\"LengthUnit\" format=\"ascii\">7 8 0</DataArray>\n"
                      "<DataArray type=\"Float32\" Name=\"TimeUnit\" format=\"ascii\">1</DataArray>\n";
    EXPECT_EQ(load_pathlines(put("c.vtp", vtp(bad)), {}, &r).units, Units{});
    EXPECT_TRUE(has(r, "field data 'LengthUnit' holds no printable unit"));
    EXPECT_TRUE(has(r, "field data 'TimeUnit' is not a String array"));
}

TEST_F(IoUnits, NothingShowsAUnitItDoesNotKnow) {
    // Text rows: no length unit; time is seconds only when the step was given.
    const std::string rows = put("r.txt", "0 0 0 1 0 0 2 0 0\n0 1 0 1 1 0 2 1 0\n");
    EXPECT_EQ(load_pathlines(rows).units, Units{});
    LoadOptions o;
    o.time_step = 0.5;
    EXPECT_EQ(load_pathlines(rows, o).units, (Units{"", "s", ""}));
    o.units = "mm";
    EXPECT_EQ(load_pathlines(rows, o).units, (Units{"mm", "s", "mm/s"}));
    o.time_step = 0;  // the default step is a guess: a length alone gives no velocity unit
    EXPECT_EQ(load_pathlines(rows, o).units, (Units{"mm", "", ""}));
    // A VTK file with velocity but no unit field data: none.
    std::string vtk = std::string("# vtk DataFile Version 4.2\nu\nASCII\nDATASET POLYDATA\n") + kLines;
    EXPECT_EQ(load_pathlines(put("a.vtk", vtk)).units, Units{});
}

TEST_F(IoUnits, UnitsOption) {
    Units u{"", "s", ""};
    apply_units_option(u, "mm");
    EXPECT_EQ(u, (Units{"mm", "s", "mm/s"}));
    apply_units_option(u, "m,m/s");
    EXPECT_EQ(u, (Units{"m", "s", "m/s"}));
    apply_units_option(u, ",cm/s");
    EXPECT_EQ(u, (Units{"m", "s", "cm/s"}));
    Units file{"mm", "s", "m/s"};  // the file's own velocity unit survives a length-only option
    apply_units_option(file, "mm");
    EXPECT_EQ(file.velocity, "m/s");
    apply_units_option(file, "");
    EXPECT_EQ(file, (Units{"mm", "s", "m/s"}));
    Units vtk;  // a file without units (VTK): the velocity's per-time names the time's unit
    apply_units_option(vtk, "mm,m/s");
    EXPECT_EQ(vtk, (Units{"mm", "s", "m/s"}));
    Units strange;
    apply_units_option(strange, "mm,m/frame");  // no known time unit: none guessed
    EXPECT_EQ(strange, (Units{"mm", "", "m/frame"}));
    for (const char* bad : {",", "a,b,c", "m\x01", " mm", "abcdefghijklmnopqrstuvwxyz"})
        EXPECT_THROW(apply_units_option(u, bad), std::invalid_argument) << bad;
    // Through the loader: a bad spec names the file.
    LoadOptions o;
    o.units = "a,b,c";
    try {
        load_pathlines(put("r.txt", "0 0 0 1 0 0\n"), o);
        FAIL() << "expected DataError";
    } catch (const DataError& e) {
        EXPECT_NE(std::string(e.what()).find("r.txt: --units expects at most two units"), std::string::npos) << e.what();
    }
}

}  // namespace
