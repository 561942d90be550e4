// Texture sizes (relative chains), mip counts and memory estimates.
#include "graph_internal.hpp"

#include <algorithm>
#include <cmath>

namespace pathlet::graph_detail {

namespace {

// ceil(n * scale), at least 1. The epsilon keeps float scales such as 0.1f (0.100000001)
// from rounding 1000 * 0.1 up to 101.
int scaled(int n, float scale) {
    double v = std::ceil(double(n) * double(scale) - 1e-4);
    return std::max(1, int(v));
}

std::string resolve(const GraphIndex& idx, int r, glm::ivec2 output, std::vector<int>& chain, glm::ivec2& out,
                    int* at) {
    const ResourceDecl& res = idx.resources[r];
    if (at) *at = r;
    if (std::find(chain.begin(), chain.end(), r) != chain.end()) {
        // Start the cycle at its first-declared member, so every member reports the same one.
        std::vector<int> cycle(std::find(chain.begin(), chain.end(), r), chain.end());
        std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
        std::vector<std::string> names;
        for (int c : cycle) names.push_back(idx.resources[c].name);
        names.push_back(names.front());
        if (at) *at = cycle.front();
        return "size of '" + names.front() + "' is relative to itself: " + join(names, " -> ");
    }
    chain.push_back(r);
    if (!res.size) {
        // No size: the writing pin's scale of the output size.
        const PinDecl* pin = idx.writer_pin(r);
        float s = pin ? pin->scale : 1.0f;
        out = {scaled(output.x, s), scaled(output.y, s)};
        return "";
    }
    const SizeDecl& sd = *res.size;
    if (sd.relative_to.empty()) {
        out = {sd.width, sd.height};
        return "";
    }
    glm::ivec2 base = output;
    if (sd.relative_to != "output") {
        int b = idx.find_resource(sd.relative_to);
        if (b < 0) {
            auto names = idx.resource_names();
            names.push_back("output");
            return "size is relative to unknown resource '" + sd.relative_to + "'" + did_you_mean(sd.relative_to, names);
        }
        if (idx.resources[b].kind != PinKind::Texture)
            return "size is relative to '" + sd.relative_to + "', which is a buffer";
        if (std::string err = resolve(idx, b, output, chain, base, at); !err.empty()) return err;
    }
    out = {scaled(base.x, sd.scale_x), scaled(base.y, sd.scale_y)};
    return "";
}

}  // namespace

std::string resolve_size(const GraphIndex& idx, int r, glm::ivec2 output, glm::ivec2& out, int* at) {
    std::vector<int> chain;
    return resolve(idx, r, output, chain, out, at);
}

int full_mip_count(int w, int h) {
    int n = 1;
    for (int m = std::max(w, h); m > 1; m >>= 1) ++n;
    return n;
}

size_t texture_bytes(const FormatInfo& f, int w, int h, int mips) {
    size_t total = 0;
    for (int i = 0; i < mips; ++i) total += size_t(std::max(1, w >> i)) * size_t(std::max(1, h >> i)) * size_t(f.bytes_per_pixel);
    return total;
}

size_t allocated_bytes(const CompiledResource& r) { return r.history ? 2 * r.bytes : r.bytes; }

}  // namespace pathlet::graph_detail
