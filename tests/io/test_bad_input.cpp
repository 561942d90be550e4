// Bad input, one test per failure class: every problem is either repaired
// with a counted warning or rejected with a DataError "<file>: line N: ..." / "<file>:
// byte N: ...". Bad files are made here by mutating good bytes. A global operator new
// records the largest single allocation, so "no giant allocation" is checked, not assumed.
#include "io/pathline_formats.hpp"
#include "io/pathline_io.hpp"
#include "io/tract_formats.hpp"
#include "io/zlib_blocks.hpp"
#include "io_test_util.hpp"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <regex>

// The replacement operators below pair malloc with free; GCC's inliner flags the pairing.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
static std::atomic<size_t> g_largest_alloc{0};
static void record_alloc(size_t n) {
    size_t prev = g_largest_alloc.load(std::memory_order_relaxed);
    while (n > prev && !g_largest_alloc.compare_exchange_weak(prev, n)) {}
}
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PATHLET_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(PATHLET_ASAN)
// ASan owns operator new: its allocator hook records the sizes instead, so the "no giant
// allocation" checks stay real in the sanitizer build.
#include <sanitizer/allocator_interface.h>
[[maybe_unused]] static const bool g_hook_installed = [] {
    __sanitizer_install_malloc_and_free_hooks([](const volatile void*, size_t n) { record_alloc(n); },
                                              [](const volatile void*) {});
    return true;
}();
#else
void* operator new(size_t n) {
    record_alloc(n);
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, size_t) noexcept { std::free(p); }
#endif

using namespace pathlet;
using namespace pathlet::io;

namespace {

struct IoBadInput : iotest::FileTest {
    // Loads and expects a DataError that names the file, a location and `needle`.
    std::string expect_error(const std::string& path, const std::string& needle, const LoadOptions& o = {}) {
        try {
            load_pathlines(path, o);
        } catch (const DataError& e) {
            std::string m = e.what();
            EXPECT_TRUE(std::regex_search(m, std::regex("^" + std::regex_replace(path, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
                                                        ": (line|byte) [0-9]+: ")))
                << m;
            EXPECT_NE(m.find(needle), std::string::npos) << m;
            return m;
        } catch (const std::exception& e) {
            ADD_FAILURE() << "not a DataError: " << e.what();
            return "";
        }
        ADD_FAILURE() << path << ": loaded, expected an error containing '" << needle << "'";
        return "";
    }
    static bool has(const LoadReport& r, const std::string& needle) { return iotest::reports(r, needle); }
};

const char* kAscii51 =
    "# vtk DataFile Version 5.1\nt\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n0 0 0 1 0 0 2 0 0 3 0 0\n"
    "LINES 3 4\nOFFSETS vtktypeint64\n0 2 4\nCONNECTIVITY vtktypeint64\n0 1 2 3\n"
    "POINT_DATA 4\nSCALARS time float\nLOOKUP_TABLE default\n0 1 0 1\n";

std::string replace(std::string s, const std::string& from, const std::string& to) {
    auto p = s.find(from);
    EXPECT_NE(p, std::string::npos) << from;
    return p == std::string::npos ? s : s.replace(p, from.size(), to);
}

TEST_F(IoBadInput, TruncatedFilesEveryFormat) {
    Pathlines p = iotest::make_lines(6, 20);
    auto files = iotest::every_writer(p);
    files.push_back({"t.trk", write_trk(p)});  // n_count declared
    files.push_back({"t.tck", write_tck(p)});  // the end marker declares the end
    for (auto& [name, bytes] : files) {
        // Cutting anywhere never crashes; the half-way cut must be reported.
        // Every format here declares its counts up front, so every cut must fail, naming the
        // file and a place; none may load a silently shortened data set.
        for (int k = 1; k < 40; ++k) {
            std::string path = put(name, bytes.substr(0, bytes.size() * size_t(k) / 40));
            expect_error(path, "");
        }
    }
}

TEST_F(IoBadInput, CountsDisagreeWithData) {
    expect_error(put("a.vtk", replace(kAscii51, "POINTS 4", "POINTS 5")), "");  // 4.. values then "LINES" is not a number
    expect_error(put("b.vtk", replace(kAscii51, "POINT_DATA 4", "POINT_DATA 3")), "counts disagree");
    std::string v42 = "# vtk DataFile Version 4.2\nt\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n0 0 0 1 0 0 2 0 0 3 0 0\n"
                      "LINES 2 7\n2 0 1\n3 2 3 0\nPOINT_DATA 4\nSCALARS time float\nLOOKUP_TABLE default\n0 1 0 1\n";
    expect_error(put("c.vtk", replace(v42, "LINES 2 7", "LINES 2 6")), "counts disagree");
    expect_error(put("d.vtk", replace(v42, "3 2 3 0", "5 2 3 0")), "counts disagree");
    // VTP: the binary header disagrees with NumberOfPoints.
    Pathlines p = iotest::make_lines(2, 5);
    std::string vtp = write_vtp(p, {});
    std::string np = "NumberOfPoints=\"" + std::to_string(p.point_count()) + "\"";
    expect_error(put("e.vtp", replace(vtp, np, "NumberOfPoints=\"12\"")), "counts disagree");
}

TEST_F(IoBadInput, DeclaredSizesBeyondFileNoGiantAllocation) {
    Pathlines p = iotest::make_lines(2, 5);
    std::string native = dir + "/n.pathlet";
    save_pathlines(p, native, PathlineFormat::Native);
    std::string nb = iotest::read_bytes(native);
    uint64_t huge = 3'000'000'000ull;
    std::memcpy(nb.data() + 16, &huge, 8);
    g_largest_alloc = 0;
    expect_error(put("a.vtk", replace(kAscii51, "POINTS 4", "POINTS 2000000000")), "more than the");
    expect_error(put("b.vtk", replace(replace(kAscii51, "ASCII", "BINARY"), "POINTS 4", "POINTS 1500000000")), "more than the");
    expect_error(put("c.vtk", replace(kAscii51, "LINES 3 4", "LINES 3 4000000000000")), "more than the");
    expect_error(put("d.pathlet", nb), "cannot fit");
    VtpWriteOptions o;
    o.encoding = VtpWriteOptions::Encoding::AppendedRaw;
    std::string np = "NumberOfPoints=\"" + std::to_string(p.point_count()) + "\"";
    expect_error(put("e.vtp", replace(write_vtp(p, o), np, "NumberOfPoints=\"+4000000000\"")), "more than the file can hold");
    expect_error(put("f.vtp", replace(write_vtp(p, o), np, "NumberOfPoints=\"400000000\"")), "");
    EXPECT_LT(g_largest_alloc.load(), size_t(16) << 20) << "a bad count caused a large allocation";
}

TEST_F(IoBadInput, NanAndInfPointsDroppedAndLinesSplit) {
    Pathlines p = iotest::make_lines(3, 10);
    p.position[0].x = NAN;                      // line 0: first point -> just dropped
    p.position[p.lines[1].first + 4].y = INFINITY;  // line 1: middle -> split in two
    p.velocity[p.lines[2].first + p.lines[2].count - 1].z = NAN;  // line 2: last point (bad velocity) -> dropped
    for (auto fmt : {PathlineFormat::Native, PathlineFormat::VtkAscii, PathlineFormat::VtpBinary}) {
        std::string path = dir + "/nan" + (fmt == PathlineFormat::Native ? ".pathlet" : fmt == PathlineFormat::VtkAscii ? ".vtk" : ".vtp");
        save_pathlines(p, path, fmt);
        LoadReport r;
        Pathlines q = load_pathlines(path, {}, &r);
        EXPECT_EQ(q.line_count(), 4u);
        EXPECT_EQ(q.point_count(), p.point_count() - 3);
        EXPECT_TRUE(has(r, "dropped 3 non-finite (NaN/inf) points in 3 lines (split into 1 extra lines)")) << path;
        EXPECT_TRUE(q.bounds().valid());
    }
}

TEST_F(IoBadInput, ZeroLengthSegmentsDropped) {
    Pathlines p = iotest::make_lines(2, 6);
    // Repeat a point (with a later time) twice in line 0.
    auto dup = [&](uint32_t at) {
        p.position.insert(p.position.begin() + at + 1, p.position[at]);
        p.time.insert(p.time.begin() + at + 1, p.time[at] + 1e-5f);
        p.velocity.insert(p.velocity.begin() + at + 1, p.velocity[at]);
        p.lines[0].count++;
        p.lines[1].first++;
    };
    dup(2);
    dup(2);
    std::string path = dir + "/dup.pathlet";
    save_pathlines(p, path, PathlineFormat::Native);
    LoadReport r;
    Pathlines q = load_pathlines(path, {}, &r);
    EXPECT_EQ(q.point_count(), p.point_count() - 2);
    EXPECT_TRUE(has(r, "dropped 2 duplicate consecutive points (zero-length segments) in 1 lines")) << r.warnings.size();
}

TEST_F(IoBadInput, OnePointLinesDropped) {
    std::string s = replace(kAscii51, "0 2 4", "0 1 4");  // lines of 1 and 3 points
    LoadReport r;
    Pathlines q = load_pathlines(put("a.vtk", replace(s, "0 1 0 1\n", "0 0 1 2\n")), {}, &r);
    EXPECT_EQ(q.line_count(), 1u);
    EXPECT_EQ(q.point_count(), 3u);
    EXPECT_TRUE(has(r, "dropped 1 lines with fewer than 2 distinct points"));
    EXPECT_TRUE(has(r, "derived velocity by finite differences"));
}

TEST_F(IoBadInput, MissingTimeDerivedFromVelocityOrClearError) {
    std::string no_time = replace(kAscii51, "SCALARS time float\nLOOKUP_TABLE default\n0 1 0 1\n",
                                  "VECTORS velocity float\n2 0 0 2 0 0 1 0 0 1 0 0\n");
    LoadReport r;
    Pathlines q = load_pathlines(put("a.vtk", no_time), {}, &r);
    ASSERT_EQ(q.line_count(), 2u);
    EXPECT_FLOAT_EQ(q.time[1], 0.5f);  // 1 unit at speed 2
    EXPECT_FLOAT_EQ(q.time[3], 1.0f);  // 1 unit at speed 1
    EXPECT_TRUE(has(r, "derived time from arc length / speed"));
    std::string neither = replace(kAscii51, "SCALARS time float", "SCALARS pressure float");
    std::string m = expect_error(put("b.vtk", neither), "Point arrays present: pressure (1 comp)");
    EXPECT_NE(m.find("--time-array"), std::string::npos);
    // Naming the array fixes it.
    LoadOptions o;
    o.time_array = "pressure";
    EXPECT_EQ(load_pathlines(put("b.vtk", neither), o).line_count(), 2u);
}

TEST_F(IoBadInput, DecompressionBombCapped) {
    Pathlines p = iotest::make_lines(1, 3);  // 3 points: Points array is 36 bytes
    VtpWriteOptions o;
    o.encoding = VtpWriteOptions::Encoding::AppendedRaw;
    o.zlib = true;
    o.header64 = false;
    std::string good = write_vtp(p, o);
    // Replace the Points array's blocks with 64 MiB of zeros (~64 KiB compressed) whose header
    // claims 36 bytes: inflating must stop at the claim.
    std::string bomb_body = zlib_blocks_encode(std::string(64u << 20, '\0'), 4, false, 64u << 20);
    std::string bomb = bomb_body;
    uint32_t small = 36;
    std::memcpy(bomb.data() + 4, &small, 4);  // block size
    std::memcpy(bomb.data() + 8, &small, 4);  // last block size
    size_t marker = good.find("   _") + 4;
    size_t points_off = std::stoul(good.substr(good.find("offset=\"", good.find("Name=\"Points\"")) + 8));
    std::string hacked = good.substr(0, marker);
    // Points is written third (after time and velocity); put the bomb at the end and point there.
    std::string appended = good.substr(marker);
    size_t bomb_at = appended.rfind("\n  </AppendedData>");
    appended.insert(bomb_at, bomb);
    hacked += appended;
    hacked = replace(hacked, "Name=\"Points\" NumberOfComponents=\"3\" format=\"appended\" offset=\"" + std::to_string(points_off),
                     "Name=\"Points\" NumberOfComponents=\"3\" format=\"appended\" offset=\"" + std::to_string(bomb_at));
    g_largest_alloc = 0;
    expect_error(put("bomb.vtp", hacked), "decompression bomb");
    EXPECT_LT(g_largest_alloc.load(), size_t(1) << 20);
    // A header that declares the full 64 MiB disagrees with the 36-byte array: rejected before inflating.
    std::string honest = good.substr(0, marker) + appended.substr(0, bomb_at) + bomb_body + appended.substr(bomb_at);
    honest = replace(honest, "offset=\"" + std::to_string(points_off) + "\"", "offset=\"" + std::to_string(bomb_at) + "\"");
    g_largest_alloc = 0;
    expect_error(put("bomb2.vtp", honest), "array needs 36");
    EXPECT_LT(g_largest_alloc.load(), size_t(1) << 20);
}

TEST_F(IoBadInput, WrongByteOrderDetected) {
    // A "BINARY" legacy file whose payload is little-endian (a common hand-written mistake).
    auto le = [](auto v) { return std::string(reinterpret_cast<const char*>(&v), sizeof v); };
    std::string pts;
    for (float f : {0.5f, 1.25f, 2.0f, 1.5f, 0.75f, 3.0f, 2.5f, 1.0f, 4.0f}) pts += le(f);
    std::string head = "# vtk DataFile Version 4.2\nt\nBINARY\nDATASET POLYDATA\nPOINTS 3 float\n";
    std::string m = expect_error(put("a.vtk", head + pts + "\nLINES 1 4\n"), "little-endian");
    // Points that are plausible either way: the cell sizes give it away.
    std::string ints = le(int32_t(3)) + le(int32_t(0)) + le(int32_t(1)) + le(int32_t(2));
    std::string zeros(36, '\0');
    expect_error(put("b.vtk", head + zeros + "\nLINES 1 4\n" + ints + "\n"), "little-endian");
    // 5.1 offsets.
    std::string h51 = replace(head, "4.2", "5.1");
    std::string off = le(int64_t(0)) + le(int64_t(3));
    std::string conn = le(int64_t(0)) + le(int64_t(1)) + le(int64_t(2));
    expect_error(put("c.vtk", h51 + zeros + "\nLINES 2 3\nOFFSETS vtktypeint64\n" + off + "\nCONNECTIVITY vtktypeint64\n" + conn + "\n"),
                 "little-endian");
}

TEST_F(IoBadInput, NonMonotonicTimeSortedOrReversed) {
    // Decision: a line whose time only decreases is reversed; any other disorder is sorted
    // by time (stable), and points repeating the previous time are dropped. All warned.
    std::string s = replace(kAscii51, "0 1 0 1\n", "1 0 0 1\n");  // line 0 decreasing, line 1 increasing
    LoadReport r;
    Pathlines q = load_pathlines(put("a.vtk", s), {}, &r);
    ASSERT_EQ(q.line_count(), 2u);
    EXPECT_EQ(q.position[0], glm::vec3(1, 0, 0));
    EXPECT_TRUE(has(r, "reversed 1 lines"));
    std::string s2 = "# vtk DataFile Version 4.2\nt\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n0 0 0 1 0 0 2 0 0 3 0 0\n"
                     "LINES 1 5\n4 0 1 2 3\nPOINT_DATA 4\nSCALARS time float\nLOOKUP_TABLE default\n0 2 1 3\n";
    LoadReport r2;
    Pathlines q2 = load_pathlines(put("b.vtk", s2), {}, &r2);
    ASSERT_EQ(q2.point_count(), 4u);
    EXPECT_EQ(q2.position[1], glm::vec3(2, 0, 0));
    EXPECT_FLOAT_EQ(q2.time[1], 1.0f);
    EXPECT_TRUE(has(r2, "sorted 1 lines by time"));
}

TEST_F(IoBadInput, IndexBeyondPointCount) {
    expect_error(put("a.vtk", replace(kAscii51, "0 1 2 3\n", "0 1 2 99\n")), "point index 99, but there are only 4 points");
    Pathlines p = iotest::make_lines(1, 4);
    VtpWriteOptions o;
    o.encoding = VtpWriteOptions::Encoding::Ascii;
    expect_error(put("b.vtp", replace(write_vtp(p, o), "0 1 2 3 \n", "0 1 7 3 \n")), "point index 7");
}

TEST_F(IoBadInput, OffsetsNotMonotone) {
    expect_error(put("a.vtk", replace(replace(kAscii51, "LINES 3 4", "LINES 4 4"), "0 2 4", "0 3 1 4")), "not monotone");
    Pathlines p = iotest::make_lines(2, 4);  // offsets "4 9"
    VtpWriteOptions o;
    o.encoding = VtpWriteOptions::Encoding::Ascii;
    expect_error(put("b.vtp", replace(write_vtp(p, o), ">\n          4 9 \n", ">\n          9 4 \n")), "not monotone");
}

TEST_F(IoBadInput, EmptyDatasetIsEmptyWithWarning) {
    // Decision: an empty file of a known format is an empty Pathlines plus a warning (the
    // renderer draws an empty frame); a corrupt one is an error.
    std::string s = "# vtk DataFile Version 5.1\nt\nASCII\nDATASET POLYDATA\nPOINTS 0 float\n";
    LoadReport r;
    EXPECT_TRUE(load_pathlines(put("a.vtk", s), {}, &r).empty());
    EXPECT_TRUE(has(r, "empty pathline set"));
    LoadReport r2;
    EXPECT_TRUE(load_pathlines(put("rows", "\n\n"), {}, &r2).empty());
    EXPECT_TRUE(has(r2, "empty pathline set"));
}

TEST_F(IoBadInput, UnsupportedThingsSayWhatToDo) {
    Pathlines p = iotest::make_lines(1, 4);
    VtpWriteOptions o;
    o.zlib = true;
    expect_error(put("a.vtp", replace(write_vtp(p, o), "vtkZLibDataCompressor", "vtkLZ4DataCompressor")), "only vtkZLibDataCompressor");
    expect_error(put("b.vtk", replace(kAscii51, "POLYDATA", "UNSTRUCTURED_GRID")), "must be POLYDATA");
    expect_error(put("c.vtk", replace(kAscii51, "POINT_DATA 4", "GARBAGE 4")), "unexpected keyword 'GARBAGE'");
    std::string native = dir + "/n.pathlet";
    save_pathlines(p, native, PathlineFormat::Native);
    std::string nb = iotest::read_bytes(native);
    nb[8] = 9;
    expect_error(put("d.pathlet", nb), "version 9 is not supported");
    expect_error(put("rows.txt", "1 2 3 4 5 6\n1 2 3 4 5\n"), "not a multiple of 3");
    std::string m = expect_error(put("rows2.txt", "1 2 3 4 5 6\n1 2 x 4 5 6\n"), "'x' is not a number");
    EXPECT_NE(m.find(": line 2: "), std::string::npos) << m;
}

// ---- defects an outside fuzzing run found -----------------------------------------------------

TEST_F(IoBadInput, CellCountBeyondTheValuesIsRefusedBeforeAllocating) {
    // 4.2 layout: "LINES n size" with a huge n and a handful of values reserved n offsets.
    const std::string v42 =
        "# vtk DataFile Version 4.2\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 2 0 0\n"
        "LINES 2000000000 4\n3 0 1 2\n";
    g_largest_alloc = 0;
    expect_error(put("cells.vtk", v42), "declares 2000000000 cells but only 4 values");
    EXPECT_LT(g_largest_alloc.load(), size_t(1) << 20) << "the cell count sized an allocation";
}

TEST_F(IoBadInput, NonIntegerIndicesAreErrorsNotUndefinedBehaviour) {
    for (const char* bad : {"nan", "inf", "-inf", "1e20", "-1e300"}) {
        expect_error(put("conn.vtk", replace(kAscii51, "CONNECTIVITY vtktypeint64\n0 1 2 3",
                                             std::string("CONNECTIVITY vtktypeint64\n0 1 ") + bad + " 3")),
                     "not a number");
        expect_error(put("offs.vtk", replace(kAscii51, "OFFSETS vtktypeint64\n0 2 4",
                                             std::string("OFFSETS vtktypeint64\n0 ") + bad + " 4")),
                     "not a number");
    }
}

TEST_F(IoBadInput, OneHugeCoordinateIsDroppedAloneNotTheWholeDataSet) {
    Pathlines p = iotest::make_lines(5, 40);
    p.position[p.lines[2].first + 7] = glm::vec3(3e38f, 0.0f, 0.0f);  // finite, but overflows the diagonal
    std::string path = dir + "/outlier.pathlet";
    save_pathlines(p, path, PathlineFormat::Native);
    LoadReport r;
    Pathlines q = load_pathlines(path, {}, &r);
    EXPECT_EQ(q.line_count(), 6u) << "the outlier splits its line; nothing else is lost";
    EXPECT_EQ(q.point_count(), p.point_count() - 1);
    EXPECT_TRUE(has(r, "dropped 1 outlying points")) << (r.warnings.empty() ? "" : r.warnings[0]);
    EXPECT_FALSE(has(r, "duplicate"));
}

TEST_F(IoBadInput, EmptyFilesAreErrorsNamingTheFile) {
    for (const char* name : {"empty.pathlet", "empty.vtk", "empty.vtp", "empty.txt", "empty"})
        expect_error(put(name, ""), "the file is empty");
}

TEST_F(IoBadInput, ZlibHeadersClaimingMoreThanDeflateCanProduceAreRefused) {
    ZlibBlockHeader h;
    h.blocks = 1000;
    h.block_size = 1 << 20;
    h.compressed.assign(1000, 12);  // 1 MiB from 12 bytes: impossible for deflate
    EXPECT_NE(zlib_blocks_implausible(h), "");
    h.compressed.assign(1000, 2000);  // ~524:1, possible for zeros
    EXPECT_EQ(zlib_blocks_implausible(h), "");
}

TEST_F(IoBadInput, TheAllocationRecorderSeesAllocations) {
    // The "no giant allocation" checks above are only as good as the recorder: in the plain
    // build it is a replaced operator new, under ASan the allocator's malloc hook.
    g_largest_alloc = 0;
    auto big = std::make_unique<std::vector<char>>(size_t(64) << 20);
    EXPECT_GE(g_largest_alloc.load(), size_t(64) << 20);
    EXPECT_EQ(big->size(), size_t(64) << 20);
}

void put_i32(std::string& b, size_t at, int32_t v) { std::memcpy(b.data() + at, &v, 4); }
void put_i16(std::string& b, size_t at, int16_t v) { std::memcpy(b.data() + at, &v, 2); }
void put_f32(std::string& b, size_t at, float v) { std::memcpy(b.data() + at, &v, 4); }

TEST_F(IoBadInput, TrackVisHeadersAndTracks) {
    Pathlines p = iotest::make_lines(3, 5);
    const std::string good = write_trk(p);
    EXPECT_EQ(load_pathlines(put("ok.trk", good)).line_count(), 3u);
    auto with = [&](auto change) {
        std::string b = good;
        change(b);
        return b;
    };
    expect_error(put("a.trk", good.substr(0, 600)), "header is 1000 bytes but the file has only 600");
    expect_error(put("b.trk", with([](std::string& b) { b[0] = 'X'; })), "magic \"TRACK\" is missing");
    expect_error(put("c.trk", with([](std::string& b) { put_i32(b, 996, 999); })), "hdr_size is 999");
    expect_error(put("d.trk", with([](std::string& b) { put_i32(b, 992, 3); })), "version 3 is not supported");
    expect_error(put("e.trk", with([](std::string& b) { put_i16(b, 36, -2); })), "n_scalars -2 is out of range");
    expect_error(put("f.trk", with([](std::string& b) { put_i16(b, 238, 5000); })), "n_properties 5000 is out of range");
    expect_error(put("g.trk", with([](std::string& b) { put_f32(b, 16, 0.0f); })), "voxel size 0 must be positive");
    expect_error(put("h.trk", with([](std::string& b) { put_f32(b, 444, NAN); })), "vox_to_ras holds a non-finite value");
    expect_error(put("i.trk", with([](std::string& b) { put_i32(b, 988, -1); })), "n_count -1 is negative");
    expect_error(put("j.trk", with([](std::string& b) { put_i32(b, 988, 7); })), "declares 7 tracks but the file ends after 3");
    // The first track's point count: negative, or more than the file holds (no giant allocation).
    expect_error(put("k.trk", with([](std::string& b) { put_i32(b, 1000, -4); })), "negative point count -4");
    g_largest_alloc = 0;
    expect_error(put("l.trk", with([](std::string& b) { put_i32(b, 1000, 2000000000); })), "declares 2000000000 points");
    EXPECT_LT(g_largest_alloc.load(), size_t(64) << 20);
    // n_scalars larger than the data: the points no longer fit.
    expect_error(put("m.trk", with([](std::string& b) { put_i16(b, 36, 40); })), "file truncated, or a corrupt count");
    // Extra bytes after the declared tracks: read, and said.
    LoadReport r;
    EXPECT_EQ(load_pathlines(put("n.trk", good + std::string(12, '\0')), {}, &r).line_count(), 3u);
    EXPECT_TRUE(has(r, "ignored 12 bytes after the 3 tracks"));
    // n_count 0 means "unknown": every track to the end of the file.
    EXPECT_EQ(load_pathlines(put("o.trk", with([](std::string& b) { put_i32(b, 988, 0); }))).line_count(), 3u);
    // NaN points are dropped and their track split, like every other reader (the repair step).
    LoadReport r2;
    Pathlines q = load_pathlines(put("p.trk", with([](std::string& b) { put_f32(b, 1004 + 12 * 2, NAN); })), {}, &r2);
    EXPECT_EQ(q.line_count(), 4u);
    EXPECT_TRUE(has(r2, "dropped 1 non-finite (NaN/inf) points in 1 lines (split into 1 extra lines)"));
}

TEST_F(IoBadInput, MrtrixTckHeadersAndData) {
    Pathlines p = iotest::make_lines(3, 5);
    const std::string good = write_tck(p);
    EXPECT_EQ(load_pathlines(put("ok.tck", good)).line_count(), 3u);
    auto sub = [&](const std::string& from, const std::string& to) { return replace(good, from, to); };
    expect_error(put("a.tck", "mrtrix image\nEND\n"), "the first line must be 'mrtrix tracks'");
    expect_error(put("b.tck", good.substr(0, good.find("END"))), "the header has no END line");
    expect_error(put("c.tck", sub("datatype: Float32LE", "datatype: Int16LE")), "datatype 'Int16LE' is not supported");
    expect_error(put("d.tck", sub("datatype: Float32LE\n", "")), "the header has no 'datatype:' line");
    expect_error(put("e.tck", sub("file: . ", "file: other.dat ")), "the data must be in this file");
    expect_error(put("f.tck", sub("file: . 00", "file: . 99")), "the data offset must lie between");
    expect_error(put("g.tck", sub("count: 3\n", "count 3\n")), "is not 'key: value'");
    expect_error(put("h.tck", good.substr(0, good.size() - 12)), "without the end-of-file marker");
    // A wrong count is a warning (MRtrix writes it at the end: an interrupted write leaves 0).
    LoadReport r;
    EXPECT_EQ(load_pathlines(put("i.tck", sub("count: 3\n", "count: 5\n")), {}, &r).line_count(), 3u);
    EXPECT_TRUE(has(r, "the header says count: 5 but the file holds 3 tracks"));
    // A header without END within its first MiB is refused without reading on.
    std::string endless = "mrtrix tracks\n";
    while (endless.size() < (2u << 20)) endless += "key: value\n";
    expect_error(put("j.tck", endless), "no END line in the first 1 MiB");
}

}  // namespace
