#include "cull_scan.hpp"

#include <cstddef>
#include <stdexcept>

namespace pathlet::lines {

namespace {

constexpr uint32_t kTop = 0xffffffffu;  // line_cull_scan.comp's kTop: no level above
constexpr uint32_t kMaxGroups = 65535;  // GL 4.5's minimum GL_MAX_COMPUTE_WORK_GROUP_COUNT

// Values per level: the chunks, then each level's block count, until one block holds them.
std::vector<uint32_t> levels(size_t chunks, uint32_t per_thread) {
    const size_t block = size_t(CullScan::kThreads) * per_thread;
    if (chunks > size_t(kMaxGroups) * block)
        throw std::length_error("line kit culling: " + std::to_string(chunks) + " chunks; the scan takes at most " +
                                std::to_string(size_t(kMaxGroups) * block));
    std::vector<uint32_t> n{uint32_t(chunks)};
    while (n.back() > block) n.push_back(uint32_t((n.back() + block - 1) / block));
    return n;
}

}  // namespace

size_t CullScan::scratch_words(size_t chunks, uint32_t per_thread) {
    const std::vector<uint32_t> n = levels(chunks, per_thread);
    size_t words = 0;
    for (size_t k = 1; k < n.size(); ++k) words += n[k];
    return std::max<size_t>(words, 1);
}

std::vector<std::string> CullScan::defines(uint32_t per_thread) {
    return {"CULL_SCAN_THREADS " + std::to_string(kThreads), "CULL_SCAN_PER_THREAD " + std::to_string(per_thread)};
}

void CullScan::run(const ShaderProgram& scan, GLuint header, uint32_t chunks, int phase, uint32_t per_thread) {
    const std::vector<uint32_t> n = levels(chunks, per_thread);
    std::vector<uint32_t> at(n.size(), 0);  // level k > 0: where its values start in the scratch
    for (size_t k = 2; k < n.size(); ++k) at[k] = at[k - 1] + n[k - 1];
    if (phase == 1) {  // the counts add up from zero; phase 2 draws nothing until it runs
        const GLintptr from = offsetof(CullHeader, cmd[1]);
        glClearNamedBufferSubData(header, GL_R32UI, from, GLsizeiptr(sizeof(CullHeader) - size_t(from)), GL_RED_INTEGER,
                                  GL_UNSIGNED_INT, nullptr);
    }
    scan.use();
    scan.set("u_cull_phase", phase);
    auto step = [&](size_t k, bool reduce, uint32_t out, uint32_t groups) {
        set_uint(scan, "u_cull_count", n[k]);
        set_uint(scan, "u_cull_in", at[k]);
        set_uint(scan, "u_cull_out", out);
        scan.set("u_cull_level0", k == 0 ? 1 : 0);
        scan.set("u_cull_reduce", reduce ? 1 : 0);
        glDispatchCompute(groups, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    };
    const size_t top = n.size() - 1;
    for (size_t k = 0; k < top; ++k) step(k, true, at[k + 1], n[k + 1]);
    step(top, false, kTop, 1);
    for (size_t k = top; k-- > 0;) step(k, false, at[k + 1], n[k + 1]);
}

}  // namespace pathlet::lines
