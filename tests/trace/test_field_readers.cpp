// Velocity-volume readers: every encoding round-trips a small field; bad input is a
// DataError naming the file and place.
#include "trace/field_readers.hpp"
#include "trace/vti_codec.hpp"
#include "util/atomic_file.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <fstream>

using namespace pathlet;
using namespace pathlet::trace;

namespace {

const glm::ivec3 kDims(3, 4, 2);
glm::vec3 vel(size_t i) { return {float(i), 0.5f * float(i), -float(i)}; }

std::string temp(const std::string& name) {
    const auto dir = std::filesystem::path(PATHLET_TEST_BINARY_DIR) / "trace-readers";
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

std::string write(const std::string& name, const std::string& bytes) {
    const std::string p = temp(name);
    write_file_atomic(p, bytes);
    return p;
}

size_t count() { return size_t(kDims.x) * kDims.y * kDims.z; }

std::string be32(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return {char(u >> 24), char(u >> 16), char(u >> 8), char(u)};
}

std::string vtk_legacy(bool binary) {
    std::string s = "# vtk DataFile Version 3.0\ntest\n" + std::string(binary ? "BINARY" : "ASCII") +
                    "\nDATASET STRUCTURED_POINTS\nDIMENSIONS 3 4 2\nASPECT_RATIO 2 2 2\nORIGIN 1 2 3\nPOINT_DATA 24\n"
                    "SCALARS speed float 1\nLOOKUP_TABLE default\n";
    for (size_t i = 0; i < count(); ++i) s += binary ? be32(float(i)) : std::to_string(i) + " ";
    s += "\nVECTORS velocity float\n";
    for (size_t i = 0; i < count(); ++i)
        for (int c = 0; c < 3; ++c) s += binary ? be32(vel(i)[c]) : std::to_string(vel(i)[c]) + " ";
    return s + "\n";
}

std::string base64(const std::string& in) {
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < in.size(); i += 3) {
        uint32_t v = uint32_t(uint8_t(in[i])) << 16;
        if (i + 1 < in.size()) v |= uint32_t(uint8_t(in[i + 1])) << 8;
        if (i + 2 < in.size()) v |= uint32_t(uint8_t(in[i + 2]));
        out += t[v >> 18 & 63];
        out += t[v >> 12 & 63];
        out += i + 1 < in.size() ? t[v >> 6 & 63] : '=';
        out += i + 2 < in.size() ? t[v & 63] : '=';
    }
    return out;
}

std::string le32(uint32_t u) { return {char(u), char(u >> 8), char(u >> 16), char(u >> 24)}; }

// The block VTK writes for one array: raw = [size][data], zlib = one compressed block.
std::string block(const std::string& data, bool zlib) {
    if (!zlib) return le32(uint32_t(data.size())) + data;
    uLongf n = compressBound(uLong(data.size()));
    std::string c(n, '\0');
    compress(reinterpret_cast<Bytef*>(c.data()), &n, reinterpret_cast<const Bytef*>(data.data()), uLong(data.size()));
    c.resize(n);
    return le32(1) + le32(uint32_t(data.size())) + le32(uint32_t(data.size())) + le32(uint32_t(c.size())) + c;
}

// format: ascii | binary | raw | base64 ; zlib compresses binary payloads.
std::string make_vti(const std::string& format, bool zlib) {
    std::string vel_bytes, mask_bytes, vel_text, mask_text;
    for (size_t i = 0; i < count(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const float f = vel(i)[c];
            vel_bytes.append(reinterpret_cast<const char*>(&f), 4);
            vel_text += std::to_string(f) + " ";
        }
        const float m = i % 2 ? 1.0f : 0.0f;
        mask_bytes.append(reinterpret_cast<const char*>(&m), 4);
        mask_text += std::to_string(m) + " ";
    }
    std::string x = "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt32\"";
    if (zlib) x += " compressor=\"vtkZLibDataCompressor\"";
    x += ">\n<ImageData WholeExtent=\"0 2 0 3 0 1\" Origin=\"1 2 3\" Spacing=\"2 2 2\">\n<Piece Extent=\"0 2 0 3 0 1\">\n"
         "<PointData Vectors=\"velocity\">\n";
    const bool appended = format == "raw" || format == "base64";
    const std::string vb = block(vel_bytes, zlib), mb = block(mask_bytes, zlib);
    auto array = [&](const std::string& name, int comps, const std::string& text, const std::string& blk, size_t offset) {
        x += "<DataArray type=\"Float32\" Name=\"" + name + "\" NumberOfComponents=\"" + std::to_string(comps) + "\" format=\"" +
             (appended ? "appended" : format) + "\"";
        if (appended) x += " offset=\"" + std::to_string(offset) + "\"/>\n";
        else x += ">" + (format == "ascii" ? text : base64(blk)) + "</DataArray>\n";
    };
    const std::string vpart = format == "base64" ? base64(vb) : vb;
    array("velocity", 3, vel_text, vb, 0);
    array("mask", 1, mask_text, mb, vpart.size());
    x += "</PointData>\n</Piece>\n</ImageData>\n";
    if (appended)
        x += "<AppendedData encoding=\"" + format + "\">\n_" + vpart + (format == "base64" ? base64(mb) : mb) + "\n</AppendedData>\n";
    return x + "</VTKFile>\n";
}

void expect_field(const VelocityField& f, bool has_mask) {
    EXPECT_EQ(f.grid.dims, kDims);
    EXPECT_EQ(f.grid.origin, glm::vec3(1, 2, 3));
    EXPECT_EQ(f.grid.spacing, glm::vec3(2));
    ASSERT_EQ(f.frames.size(), 1u);
    for (size_t i = 0; i < count(); ++i) EXPECT_NEAR(glm::length(f.frames[0][i] - vel(i)), 0.0f, 1e-4f) << i;
    if (has_mask) {
        ASSERT_EQ(f.mask.size(), count());
        EXPECT_EQ(f.mask[3], 1.0f);
        EXPECT_EQ(f.mask[4], 0.0f);
    }
}

template <class Fn>
void expect_data_error(Fn fn, const std::string& must_contain) {
    try {
        fn();
        ADD_FAILURE() << "no DataError; expected one mentioning '" << must_contain << "'";
    } catch (const DataError& e) {
        EXPECT_NE(std::string(e.what()).find(must_contain), std::string::npos) << e.what();
    }
}

}  // namespace

TEST(FieldReaders, VtkLegacyAsciiAndBinary) {
    for (bool binary : {false, true}) {
        const VelocityField f = load_velocity_field(write(binary ? "b.vtk" : "a.vtk", vtk_legacy(binary)));
        expect_field(f, false);
        ASSERT_EQ(f.scalars.size(), count());
        EXPECT_EQ(f.scalars[7], 7.0f);
        EXPECT_EQ(f.scalars_name, "speed");
    }
}

TEST(FieldReaders, VtiEveryEncoding) {
    for (const std::string fmt : {"ascii", "binary", "raw", "base64"})
        for (bool zlib : {false, true}) {
            if (fmt == "ascii" && zlib) continue;
            SCOPED_TRACE(fmt + (zlib ? " zlib" : ""));
            expect_field(load_velocity_field(write("f-" + fmt + (zlib ? "-z" : "") + ".vti", make_vti(fmt, zlib))), true);
        }
}

TEST(FieldReaders, Base64ConcatenatedStreams) {
    EXPECT_EQ(vti::base64_decode("QQ==QkM="), "ABC");  // two padded streams back to back
    EXPECT_THROW(vti::base64_decode("Q!=="), std::runtime_error);
}

TEST(FieldReaders, VtkLegacyBadInput) {
    const std::string good = vtk_legacy(true);
    expect_data_error([&] { load_velocity_field(write("trunc.vtk", good.substr(0, good.size() - 40))); }, "trunc.vtk: line");
    std::string big = good;
    big.replace(big.find("POINT_DATA 24"), 13, "POINT_DATA 99");
    expect_data_error([&] { load_velocity_field(write("big.vtk", big)); }, "does not match DIMENSIONS");
    std::string huge = good;
    huge.replace(huge.find("DIMENSIONS 3 4 2"), 16, "DIMENSIONS 3000 4000 20");
    huge.replace(huge.find("POINT_DATA 24"), 13, "POINT_DATA 240000000");
    expect_data_error([&] { load_velocity_field(write("huge.vtk", huge)); }, "bytes remain");
    std::string novec = good.substr(0, good.find("VECTORS"));
    expect_data_error([&] { load_velocity_field(write("novec.vtk", novec)); }, "no VECTORS");
    std::string poly = good;
    poly.replace(poly.find("STRUCTURED_POINTS"), 17, "POLYDATA");
    expect_data_error([&] { load_velocity_field(write("poly.vtk", poly)); }, "STRUCTURED_POINTS");
}

TEST(FieldReaders, VtiBadInput) {
    const std::string raw = make_vti("raw", false);
    expect_data_error([&] { load_velocity_field(write("trunc.vti", raw.substr(0, raw.size() - 150))); }, "trunc.vti: byte");
    std::string huge = make_vti("binary", true);
    for (int k = 0; k < 2; ++k) huge.replace(huge.find("0 2 0 3 0 1"), 11, "0 20000 0 30000 0 1000");
    expect_data_error([&] { load_velocity_field(write("huge.vti", huge)); }, "exceeds");
    std::string novel = make_vti("ascii", false);
    novel.replace(novel.find("NumberOfComponents=\"3\""), 22, "NumberOfComponents=\"2\"");
    expect_data_error([&] { load_velocity_field(write("novel.vti", novel)); }, "velocity");
    std::string badz = make_vti("raw", true);
    badz[badz.find('_') + 20] ^= 0x55;  // corrupt the compressed stream
    expect_data_error([&] { load_velocity_field(write("badz.vti", badz)); }, "badz.vti: byte");
}

// A tiny 4DFlowNet-style file: u, v, w, mask of shape (1, 2, 3, 4), and dx.
static void write_tiny_h5(const std::string& path) {
    hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hsize_t dims[4] = {1, 2, 3, 4};
    hid_t space = H5Screate_simple(4, dims, nullptr);
    std::vector<float> data(24);
    for (const char* name : {"u", "v", "w", "mask"}) {
        for (size_t i = 0; i < 24; ++i) data[i] = name[0] == 'm' ? 1.0f : float(i) * (name[0] - 'u' + 1) * 1e-3f;
        hid_t d = H5Dcreate2(f, name, H5T_NATIVE_FLOAT, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        H5Dwrite(d, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data());
        H5Dclose(d);
    }
    const hsize_t one[2] = {1, 3};
    hid_t s2 = H5Screate_simple(2, one, nullptr);
    hid_t d = H5Dcreate2(f, "dx", H5T_NATIVE_FLOAT, s2, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const float dx[3] = {0.5f, 0.5f, 0.5f};
    H5Dwrite(d, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, dx);
    H5Dclose(d);
    H5Sclose(s2);
    H5Sclose(space);
    H5Fclose(f);
}

TEST(FieldReaders, Hdf5Layout) {
    const std::string path = temp("tiny.h5");
    write_tiny_h5(path);
    const VelocityField f = load_velocity_field(path);
    EXPECT_EQ(f.grid.dims, glm::ivec3(4, 3, 2));  // (i, j, k) = (2, 3, 4) -> x = k, y = j, z = i
    EXPECT_EQ(f.grid.spacing, glm::vec3(0.5f));
    // Element (i=1, j=2, k=3) is flat index 23 -> grid (3, 2, 1); velocity (w, v, u) in mm/s.
    const glm::vec3 v = f.frames[0][f.grid.index(3, 2, 1)];
    EXPECT_NEAR(v.x, 23 * 3.0f, 1e-3f);
    EXPECT_NEAR(v.y, 23 * 2.0f, 1e-3f);
    EXPECT_NEAR(v.z, 23 * 1.0f, 1e-3f);
    EXPECT_EQ(f.vessel_voxels(), 24u);
}

TEST(FieldReaders, Hdf5BadInput) {
    // Truncated: the first kilobyte of a valid file.
    {
        const std::string path = temp("tiny_for_truncation.h5");  // its own file: no order between tests
        write_tiny_h5(path);
        std::ifstream in(path, std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), {});
        expect_data_error([&] { load_velocity_field(write("trunc.h5", bytes.substr(0, 1000))); }, "trunc.h5");
    }
    // Missing arrays and absurd declared sizes.
    const std::string path = temp("bad.h5");
    {
        hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
        const hsize_t dims[4] = {1, 100000, 100000, 1000}, chunk[4] = {1, 8, 8, 8};
        hid_t space = H5Screate_simple(4, dims, nullptr);
        hid_t plist = H5Pcreate(H5P_DATASET_CREATE);
        H5Pset_chunk(plist, 4, chunk);
        for (const char* name : {"u", "v"}) H5Dclose(H5Dcreate2(f, name, H5T_NATIVE_FLOAT, space, H5P_DEFAULT, plist, H5P_DEFAULT));
        H5Pclose(plist);
        H5Sclose(space);
        H5Fclose(f);
    }
    expect_data_error([&] { load_velocity_field(path); }, "'w': missing");
    {
        hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
        const hsize_t dims[1] = {4};
        hid_t space = H5Screate_simple(1, dims, nullptr);
        H5Dclose(H5Dcreate2(f, "w", H5T_NATIVE_FLOAT, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
        H5Sclose(space);
        H5Fclose(f);
    }
    expect_data_error([&] { load_velocity_field(path); }, "too large");
    expect_data_error([&] { load_velocity_field(write("text.h5", "hello")); }, "text.h5: byte 0");
}

// ---- defects an outside fuzzing run found -----------------------------------------------------

TEST(FieldReaders, VtkLegacyNonIntegerCountsAreErrorsNotUndefinedBehaviour) {
    const std::string good = vtk_legacy(false);
    for (const char* bad : {"nan", "inf", "-inf", "1e20", "2.5"}) {
        std::string s = good;
        s.replace(s.find("DIMENSIONS 3 4 2"), 16, std::string("DIMENSIONS 3 ") + bad + " 2");
        expect_data_error([&] { load_velocity_field(write("dims.vtk", s)); }, "expected an integer");
        s = good;
        s.replace(s.find("POINT_DATA 24"), 13, std::string("POINT_DATA ") + bad);
        expect_data_error([&] { load_velocity_field(write("pd.vtk", s)); }, "expected an integer");
    }
}

TEST(FieldReaders, VtkLegacyRepeatedGridAfterTheDataIsRefused) {
    // A second DIMENSIONS/POINT_DATA after VECTORS used to enlarge the point count but keep the
    // small array: a read past its end (SIGSEGV in a release build).
    const std::string good = vtk_legacy(false);
    expect_data_error([&] { load_velocity_field(write("again.vtk", good + "\nDIMENSIONS 30 40 20\nPOINT_DATA 24000\n")); },
                      "DIMENSIONS given twice");
    expect_data_error([&] { load_velocity_field(write("again2.vtk", good + "\nPOINT_DATA 24\n")); }, "POINT_DATA given twice");
}

TEST(FieldReaders, VtiAppendedDataWithoutATagIsAnError) {
    std::string s = make_vti("raw", false);
    s = s.substr(0, s.find("<AppendedData")) + "<AppendedData";  // no delimiter, no '>'
    expect_data_error([&] { load_velocity_field(write("noapp.vti", s)); }, "noapp.vti: byte");
    std::string t = make_vti("raw", false);
    t.replace(t.find("offset=\""), 8, "offset=\"-5");
    expect_data_error([&] { load_velocity_field(write("negoff.vti", t)); }, "negoff.vti: byte");
}

TEST(FieldReaders, Hdf5DeclaredSizeMustBePlausibleFromTheStoredBytes) {
    // Self-contained: 2^29 declared floats, one 16^3 chunk actually stored (16 KiB): refused
    // before the 2 GiB allocation, naming the file, the dataset and the cap.
    const std::string path = temp("declared.h5");
    {
        hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
        const hsize_t dims[3] = {1024, 1024, 512}, chunk[3] = {16, 16, 16};
        hid_t space = H5Screate_simple(3, dims, nullptr);
        hid_t plist = H5Pcreate(H5P_DATASET_CREATE);
        H5Pset_chunk(plist, 3, chunk);
        std::vector<float> one(16 * 16 * 16, 1.0f);
        const hsize_t start[3] = {0, 0, 0};
        hid_t mem = H5Screate_simple(3, chunk, nullptr);
        for (const char* name : {"u", "v", "w"}) {
            hid_t ds = H5Dcreate2(f, name, H5T_NATIVE_FLOAT, space, H5P_DEFAULT, plist, H5P_DEFAULT);
            hid_t sel = H5Scopy(space);
            H5Sselect_hyperslab(sel, H5S_SELECT_SET, start, nullptr, chunk, nullptr);
            H5Dwrite(ds, H5T_NATIVE_FLOAT, mem, sel, H5P_DEFAULT, one.data());
            H5Sclose(sel);
            H5Dclose(ds);
        }
        H5Sclose(mem);
        H5Pclose(plist);
        H5Sclose(space);
        H5Fclose(f);
    }
    expect_data_error([&] { load_velocity_field(path); }, "PATHLET_MAX_INFLATE_RATIO");
}
