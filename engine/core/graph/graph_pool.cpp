// Pooling: transients with equal descriptors and disjoint lifetimes share one physical object.
// Greedy interval colouring in order of first use, which is optimal for interval graphs: a
// resource takes the first compatible slot whose last user ended before it starts.
#include "graph_internal.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <tuple>

namespace pathlet::graph_detail {

namespace {

bool same_descriptor(const PoolSlot& s, const CompiledResource& r) {
    if (s.kind != r.kind) return false;
    if (r.kind == PinKind::Buffer) return s.bytes == r.bytes;
    return std::tie(s.internal_format, s.width, s.height, s.mips) ==
           std::tie(r.internal_format, r.width, r.height, r.mips);
}

}  // namespace

void assign_slots(CompiledGraph& cg) {
    cg.slots.clear();
    std::vector<int> order(cg.resources.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return cg.resources[a].first_use < cg.resources[b].first_use; });

    std::vector<int> busy_until;  // per slot: last_use of its latest resource
    std::vector<bool> shareable;  // per slot: holds transients only
    cg.memory_unpooled = cg.memory_pooled = 0;
    for (int ri : order) {
        CompiledResource& r = cg.resources[ri];
        cg.memory_unpooled += allocated_bytes(r);
        int slot = -1;
        if (r.transient())
            for (size_t s = 0; s < cg.slots.size() && slot < 0; ++s)
                if (shareable[s] && busy_until[s] < r.first_use && same_descriptor(cg.slots[s], r)) slot = int(s);
        if (slot < 0) {
            PoolSlot s;
            s.kind = r.kind;
            s.internal_format = r.internal_format;
            s.width = r.width;
            s.height = r.height;
            s.mips = r.mips;
            s.bytes = allocated_bytes(r);  // a history slot holds both copies
            cg.memory_pooled += s.bytes;
            slot = int(cg.slots.size());
            cg.slots.push_back(s);
            busy_until.push_back(-1);
            shareable.push_back(r.transient());
        }
        cg.slots[slot].resources.push_back(ri);
        busy_until[slot] = r.last_use;
        r.slot = slot;
    }
}

}  // namespace pathlet::graph_detail

namespace pathlet {

void keep_resources(CompiledGraph& cg, const std::vector<std::string>& names) {
    if (names.empty()) return;
    const int last = std::max(0, int(cg.passes.size()) - 1);
    for (const auto& n : names) {
        std::string why;
        const int r = cg.resolve(n, &why);
        if (r < 0) throw std::invalid_argument(why);
        cg.resources[size_t(r)].persistent = true;
        cg.resources[size_t(r)].first_use = 0;
        cg.resources[size_t(r)].last_use = last;
    }
    graph_detail::assign_slots(cg);
}

}  // namespace pathlet
