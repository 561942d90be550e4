// The culling's prefix sum (engine/lines/src/cull_scan.hpp, line_cull_scan.comp) against the
// CPU's at sizes around its invocations and blocks: 1, 255, 256, 257, a block and one past it,
// 65,537 and a million chunks, as the culler compiles it (16 chunks an invocation: two levels
// at a million) and with one chunk an invocation (blocks of 256: three levels).
// Each chunk gets random flags and a segment count; the scan's offsets (drawn chunks only),
// draw commands and counts must be the CPU's exactly, in both phases.
#include "../src/chunk_culler.hpp"
#include "../src/cull_scan.hpp"
#include "frame_capture.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <random>

using namespace pathlet;
using namespace pathlet::lines;

namespace {

// CullState in line_cull.glsl.
struct State {
    float rect[4];
    float zmin;
    uint32_t flags, count, offset;
};
static_assert(sizeof(State) == 32);
constexpr uint32_t kDrawn = 1, kOutside = 2, kPhase1 = 8, kPhase2 = 16, kOccluded = 32;
constexpr uint32_t kUnset = 0xdeadbeef;  // an offset the scan must leave alone (chunk not drawn)

uint32_t define_value(const std::string& name) {
    for (const std::string& d : ChunkCuller::defines())
        if (d.rfind(name + " ", 0) == 0) return uint32_t(std::stoul(d.substr(name.size() + 1)));
    throw std::logic_error("no define " + name);
}

template <class T>
std::vector<T> read_buffer(GLuint b, size_t n) {
    std::vector<T> out(n);
    glGetNamedBufferSubData(b, 0, GLsizeiptr(n * sizeof(T)), out.data());
    return out;
}

// The scan as the culler compiles it, or with `per_thread` chunks an invocation (a smaller
// block reaches three levels at a million chunks).
const ShaderProgram& scan_program(uint32_t per_thread) {
    static std::map<uint32_t, ShaderProgram>& programs = *new std::map<uint32_t, ShaderProgram>;  // kept to exit
    auto it = programs.find(per_thread);
    if (it != programs.end()) return it->second;
    std::vector<std::string> defines;
    for (const std::string& d : ChunkCuller::defines())
        if (d.rfind("CULL_SCAN_", 0) != 0) defines.push_back(d);
    for (const std::string& d : CullScan::defines(per_thread)) defines.push_back(d);
    return programs.emplace(per_thread, ShaderProgram::from_files({"line_cull_scan.comp"},
                                                                  {std::string(PATHLET_SOURCE_DIR) + "/engine/lines/shaders",
                                                                   std::string(PATHLET_SOURCE_DIR) + "/shaders"},
                                                                  defines))
        .first->second;
}

void expect_scan_matches_cpu(size_t n, uint32_t per_thread = CullScan::kPerThread) {
    SCOPED_TRACE(std::to_string(n) + " chunks, " + std::to_string(per_thread) + " an invocation");
    test_runtime();  // the GL context
    const ShaderProgram& scan = scan_program(per_thread);
    std::mt19937 rng{uint32_t(n)};
    std::vector<State> states(n);
    for (State& s : states) {
        s = {};
        const uint32_t r = rng();
        s.flags = (r & 1 ? kDrawn : 0) | (r & 2 ? kOutside : 0) | (r & 4 ? kPhase1 : 0) | (r & 8 ? kPhase2 : 0) |
                  (r & 16 ? kOccluded : 0);
        s.count = (r >> 8) % 9;  // 0..8 segments a chunk
        s.offset = kUnset;
    }
    GLuint state = 0, header = 0;
    glCreateBuffers(1, &state);
    glNamedBufferStorage(state, GLsizeiptr(std::max<size_t>(n, 1) * sizeof(State)), states.data(), GL_DYNAMIC_STORAGE_BIT);
    const std::vector<uint32_t> junk(CullScan::header_bytes(n, per_thread) / 4, 0x5a5a5a5a);  // the scan clears what it counts
    glCreateBuffers(1, &header);
    glNamedBufferStorage(header, GLsizeiptr(junk.size() * 4), junk.data(), 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, define_value("CULL_STATE_BINDING"), state);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, define_value("CULL_HEADER_BINDING"), header);
    CullScan::run(scan, header, uint32_t(n), 1, per_thread);
    CullScan::run(scan, header, uint32_t(n), 2, per_thread);
    const std::vector<State> got = read_buffer<State>(state, n);
    const std::vector<uint32_t> h = read_buffer<uint32_t>(header, sizeof(CullHeader) / 4);
    CullHeader gh;
    std::memcpy(&gh, h.data(), sizeof gh);

    // The CPU's: phase 1's chunks in chunk order, then phase 2's after them.
    uint32_t at = 0, seg[2] = {0, 0}, drawn[2] = {0, 0}, chunks = 0, outside = 0, occluded = 0;
    std::vector<uint32_t> offset(n, kUnset);
    for (int phase = 0; phase < 2; ++phase)
        for (size_t c = 0; c < n; ++c)
            if (states[c].flags & (phase == 0 ? kPhase1 : kPhase2)) {
                offset[c] = at;  // a chunk in both phases: phase 2's offset is the one left
                at += states[c].count;
                seg[phase] += states[c].count;
                ++drawn[phase];
            }
    for (const State& s : states) chunks += !!(s.flags & kDrawn), outside += !!(s.flags & kOutside), occluded += !!(s.flags & kOccluded);

    size_t wrong = 0, first_wrong = n;
    for (size_t c = 0; c < n; ++c)
        if (got[c].offset != offset[c] && wrong++ == 0) first_wrong = c;
    EXPECT_EQ(wrong, 0u) << "first at chunk " << first_wrong << ": " << got[first_wrong].offset << ", the CPU's "
                         << offset[first_wrong];
    EXPECT_EQ(gh.segments[0], seg[0]);
    EXPECT_EQ(gh.segments[1], seg[1]);
    const uint32_t cmd1[5] = {2 * seg[0], 1, 0, 0, 0}, cmd2[5] = {2 * seg[1], 1, 2 * seg[0], 0, 0};
    for (int k = 0; k < 5; ++k) {
        EXPECT_EQ(gh.cmd[0][k], cmd1[k]) << "phase 1's command, word " << k;
        EXPECT_EQ(gh.cmd[1][k], cmd2[k]) << "phase 2's command, word " << k;
    }
    EXPECT_EQ(gh.drawn[0], drawn[0]);
    EXPECT_EQ(gh.drawn[1], drawn[1]);
    EXPECT_EQ(gh.chunks, chunks);
    EXPECT_EQ(gh.outside, outside);
    EXPECT_EQ(gh.occluded, occluded);
    glDeleteBuffers(1, &state);
    glDeleteBuffers(1, &header);
}

TEST(CullScan, OneChunk) {
    expect_scan_matches_cpu(1);
    expect_scan_matches_cpu(1, 1);
}
TEST(CullScan, AroundTheInvocations) {
    for (uint32_t per : {CullScan::kPerThread, 1u}) {
        expect_scan_matches_cpu(255, per);
        expect_scan_matches_cpu(256, per);  // per = 1: one block exactly
        expect_scan_matches_cpu(257, per);  // per = 1: two blocks
    }
}
TEST(CullScan, AroundTheBlockSize) {
    expect_scan_matches_cpu(CullScan::kBlock);
    expect_scan_matches_cpu(CullScan::kBlock + 1);
}
TEST(CullScan, TwoLevels) {
    expect_scan_matches_cpu(65537);     // 17 blocks of 4096
    expect_scan_matches_cpu(65537, 1);  // 257 blocks of 256: their sums are two blocks, three levels
}
TEST(CullScan, AMillionChunks) {
    expect_scan_matches_cpu(1048576);     // 256 blocks of 4096: their sums are one block
    expect_scan_matches_cpu(1048576, 1);  // 4096 blocks of 256, 16 of those, one: three levels
    expect_scan_matches_cpu(1048576 + 65537, 1);  // 4353 blocks, 18, one: partial blocks at each level
}

}  // namespace
