// The culling's prefix sum for any number of chunks (private to the line kit; ChunkCuller runs
// it per phase, engine/lines/tests/test_cull_scan.cpp checks it against the CPU's). One shader,
// line_cull_scan.comp, in levels of CULL_SCAN_BLOCK values: each level is reduced to its block
// sums in the header's scratch until one block is left, that block is scanned from the phase's
// base, and each level below is scanned from the offsets its blocks got (down-sweep). Chunk
// order is kept, so the draw order is the unculled draw's. Work groups of 256 invocations and
// 1 KiB of shared memory (GL 4.5's minimum limits: 1024 and 32 KiB); up to 65,535 blocks at
// level 0 (the minimum work group count), i.e. 268 million chunks.
#pragma once

#include <pathlet/gl.hpp>
#include <pathlet/shader.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pathlet::lines {

// An unsigned uniform of one of the culling's programs (the scan's and ChunkCuller's).
inline void set_uint(const ShaderProgram& p, const char* name, uint32_t v) { glProgramUniform1ui(p.id(), p.loc(name), v); }

// The header buffer: the two phases' DrawElementsIndirectCommands, the frame's counts, then
// the scan's scratch (scratch_words(chunks) uints).
struct CullHeader {
    uint32_t cmd[2][5];
    uint32_t segments[2];
    uint32_t chunks, outside;
    uint32_t drawn[2];
    uint32_t occluded;
};

class CullScan {
public:
    // 16 chunks an invocation: llvmpipe pays per work group (with 4 the phantom's scan took
    // 1.1 ms there, with 16 0.65 ms), and 256 groups still spread a million chunks over a GPU.
    static constexpr uint32_t kThreads = 256, kPerThread = 16, kBlock = kThreads * kPerThread;

    // Uints of scratch after the CullHeader for `chunks` chunks (the levels' block sums).
    static size_t scratch_words(size_t chunks, uint32_t per_thread = kPerThread);
    // Bytes of the header buffer for `chunks` chunks.
    static size_t header_bytes(size_t chunks, uint32_t per_thread = kPerThread) {
        return sizeof(CullHeader) + 4 * scratch_words(chunks, per_thread);
    }
    // The CULL_SCAN_* defines of line_cull_scan.comp (ChunkCuller::defines() has the default's;
    // a test compiles a smaller block to reach more levels).
    static std::vector<std::string> defines(uint32_t per_thread = kPerThread);

    // Records the levels' dispatches for `phase` (1 or 2) with `scan` (line_cull_scan.comp
    // compiled with defines(per_thread)), the chunk states and the header bound at their
    // points; phase 1 first clears the counts and phase 2's command. Ends with a storage
    // barrier. Never waits.
    static void run(const ShaderProgram& scan, GLuint header, uint32_t chunks, int phase, uint32_t per_thread = kPerThread);
};

}  // namespace pathlet::lines
