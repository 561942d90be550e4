#include "fake_registry.hpp"
#include "formats.hpp"

#include <algorithm>
#include <random>
#include <sstream>

using namespace pathlet;
using namespace pathlet::test;

namespace {

// The invariants of pooling: a slot only holds resources of its descriptor whose lifetimes are
// pairwise disjoint; history, persistent and captured resources sit alone; the totals add up.
void check_slots(const CompiledGraph& cg) {
    size_t unpooled = 0, pooled = 0;
    for (const auto& r : cg.resources) {
        ASSERT_GE(r.slot, 0) << r.name;
        unpooled += r.history ? 2 * r.bytes : r.bytes;
    }
    for (size_t s = 0; s < cg.slots.size(); ++s) {
        const PoolSlot& slot = cg.slots[s];
        pooled += slot.bytes;
        ASSERT_FALSE(slot.resources.empty());
        for (size_t i = 0; i < slot.resources.size(); ++i) {
            const CompiledResource& a = cg.resources[slot.resources[i]];
            EXPECT_EQ(a.slot, int(s));
            EXPECT_EQ(a.kind, slot.kind);
            if (a.kind == PinKind::Texture) {
                EXPECT_EQ(a.internal_format, slot.internal_format) << a.name;
                EXPECT_EQ(a.width, slot.width) << a.name;
                EXPECT_EQ(a.height, slot.height) << a.name;
                EXPECT_EQ(a.mips, slot.mips) << a.name;
            } else {
                EXPECT_EQ(a.bytes, slot.bytes) << a.name;
            }
            if (!a.transient()) {
                EXPECT_EQ(slot.resources.size(), 1u) << a.name << " is not transient but shares a slot";
            }
            for (size_t j = i + 1; j < slot.resources.size(); ++j) {
                const CompiledResource& b = cg.resources[slot.resources[j]];
                EXPECT_TRUE(a.last_use < b.first_use || b.last_use < a.first_use)
                    << a.name << " [" << a.first_use << "," << a.last_use << "] and " << b.name << " [" << b.first_use << ","
                    << b.last_use << "] overlap in slot " << s;
            }
        }
    }
    EXPECT_EQ(cg.memory_unpooled, unpooled);
    EXPECT_EQ(cg.memory_pooled, pooled);
    EXPECT_LE(cg.memory_pooled, cg.memory_unpooled);
}

// m0 -> m1 -> m2 -> m3 -> m4 (captured): a chain of full-size rgba16f targets.
const char* kChain = R"json({"passes": [
    {"name": "m0", "type": "mix"}, {"name": "m1", "type": "mix", "inputs": {"a": "m0.dst"}},
    {"name": "m2", "type": "mix", "inputs": {"a": "m1.dst"}}, {"name": "m3", "type": "mix", "inputs": {"a": "m2.dst"}},
    {"name": "m4", "type": "mix", "inputs": {"a": "m3.dst"}}], "outputs": ["m4.dst"]})json";

}  // namespace

TEST(Pool, AChainNeedsTwoTransientSlots) {
    CompiledGraph cg = compile(kChain, {100, 100});
    check_slots(cg);
    ASSERT_EQ(cg.slots.size(), 3u);  // ping-pong for m0..m3, one for the captured output
    EXPECT_EQ(cg.resources[cg.find_resource("m0.dst")].slot, cg.resources[cg.find_resource("m2.dst")].slot);
    EXPECT_EQ(cg.resources[cg.find_resource("m1.dst")].slot, cg.resources[cg.find_resource("m3.dst")].slot);
    EXPECT_NE(cg.resources[cg.find_resource("m0.dst")].slot, cg.resources[cg.find_resource("m1.dst")].slot);
    const size_t one = 100 * 100 * 8;
    EXPECT_EQ(cg.memory_unpooled, 5 * one);
    EXPECT_EQ(cg.memory_pooled, 3 * one);
}

TEST(Pool, DifferentDescriptorsAreNotShared) {
    CompiledGraph cg = compile(R"json({"resources": {"big": {"format": "rgba16f", "size": {"scale": 2}},
                                                     "r8": {"format": "r8"}},
      "passes": [{"name": "a", "type": "mix"}, {"name": "b", "type": "blur", "inputs": {"src": "a.dst"}, "outputs": {"dst": "big"}},
                 {"name": "c", "type": "anyout", "outputs": {"dst": "r8"}},
                 {"name": "d", "type": "mix", "inputs": {"a": "big", "b": "r8"}}],
      "outputs": ["d.dst"]})json");
    check_slots(cg);
    EXPECT_EQ(cg.slots.size(), cg.resources.size());
    EXPECT_EQ(cg.memory_pooled, cg.memory_unpooled);
}

TEST(Pool, HistoryPersistentAndCapturedResourcesAreNeverPooled) {
    CompiledGraph cg = compile(R"json({"resources": {"h": {"format": "rgba16f", "history": true},
                                                     "p": {"format": "rgba16f", "persistent": true}},
      "passes": [{"name": "a", "type": "mix", "inputs": {"a": "h@prev"}, "outputs": {"dst": "h"}},
                 {"name": "b", "type": "mix", "inputs": {"a": "h"}},
                 {"name": "c", "type": "mix", "inputs": {"a": "b.dst"}, "outputs": {"dst": "p"}},
                 {"name": "d", "type": "mix", "inputs": {"a": "p"}},
                 {"name": "e", "type": "mix", "inputs": {"a": "d.dst"}},
                 {"name": "f", "type": "mix", "inputs": {"a": "e.dst"}},
                 {"name": "g", "type": "mix", "inputs": {"a": "f.dst"}}],
      "outputs": ["g.dst", "e.dst"]})json",
                               {64, 64});
    check_slots(cg);
    for (const char* n : {"h", "p", "e.dst", "g.dst"}) {
        const CompiledResource& r = cg.resources[cg.find_resource(n)];
        EXPECT_FALSE(r.transient()) << n;
        EXPECT_EQ(cg.slots[r.slot].resources.size(), 1u) << n;
    }
    // b.dst [1,2] and d.dst [3,4] share; f.dst [5,6] joins them.
    EXPECT_EQ(cg.resources[cg.find_resource("b.dst")].slot, cg.resources[cg.find_resource("d.dst")].slot);
    EXPECT_EQ(cg.resources[cg.find_resource("b.dst")].slot, cg.resources[cg.find_resource("f.dst")].slot);
}

TEST(Pool, BuffersPoolByByteSize) {
    CompiledGraph cg = compile(R"json({"passes": [
        {"name": "p1", "type": "particles"}, {"name": "d1", "type": "draw", "inputs": {"list": "p1.list"}},
        {"name": "p2", "type": "particles"}, {"name": "d2", "type": "draw", "inputs": {"list": "p2.list"}},
        {"name": "m", "type": "mix", "inputs": {"a": "d1.color", "b": "d2.color"}}],
      "outputs": ["m.dst"]})json",
                               {10, 10});
    check_slots(cg);
    EXPECT_EQ(cg.resources[cg.find_resource("p1.list")].slot, cg.resources[cg.find_resource("p2.list")].slot);
    EXPECT_NE(cg.resources[cg.find_resource("d1.color")].slot, cg.resources[cg.find_resource("d2.color")].slot);
}

// Random DAGs: passes read outputs of passes earlier in a hidden order, in shuffled file order,
// with random sizes and formats; the pooling invariants and the order must hold for every one.
TEST(Pool, PropertyRandomDagsNeverShareOverlappingLifetimes) {
    std::mt19937 rng(1234);
    int pooled_some = 0;
    for (int iter = 0; iter < 300; ++iter) {
        const int n = 2 + int(rng() % 14);
        std::vector<int> file_pos(n);
        for (int i = 0; i < n; ++i) file_pos[i] = i;
        std::shuffle(file_pos.begin(), file_pos.end(), rng);  // hidden order k -> file position
        std::vector<std::string> entries(n);
        std::ostringstream res;
        const char* formats[] = {"rgba16f", "rgba8", "r8"};
        const char* scales[] = {"1", "0.5"};
        bool first = true;
        for (int k = 0; k < n; ++k) {
            std::ostringstream p;
            const std::string name = std::string("p").append(std::to_string(k));  // not "p" + ...: GCC 12 -Wrestrict false positive
            const bool declared = rng() % 4 == 0;
            const bool history = declared && rng() % 5 == 0;
            p << "{\"name\": \"" << name << "\", \"type\": \"" << (declared ? "anyout" : "mix") << "\"";
            if (!declared) {
                p << ", \"inputs\": {";
                int used = 0;
                for (const char* pin : {"a", "b"})
                    if (k > 0 && rng() % 4) {
                        int src = k - 1 - int(rng() % std::min(k, 4));  // mostly recent: long chains
                        p << (used++ ? ", " : "") << "\"" << pin << "\": \"p" << src << ".dst\"";
                    }
                p << "}";
            } else {
                const std::string r = std::string("r").append(std::to_string(k));
                p << ", \"outputs\": {\"dst\": \"" << r << "\"}";
                res << (first ? "" : ",") << "\"" << r << "\": {\"format\": \"" << formats[rng() % 3]
                    << "\", \"size\": {\"scale\": " << scales[rng() % 2] << "}" << (history ? ", \"history\": true" : "") << "}";
                first = false;
            }
            p << "}";
            entries[file_pos[k]] = p.str();
        }
        std::ostringstream g;
        g << "{\"resources\": {" << res.str() << "}, \"passes\": [";
        for (int i = 0; i < n; ++i) g << (i ? ", " : "") << entries[i];
        g << "], \"outputs\": [\"p" << n - 1 << ".dst\"";
        if (rng() % 2) g << ", \"p" << rng() % n << ".dst\"";
        g << "]}";
        SCOPED_TRACE(g.str());
        CompiledGraph cg = compile(g.str(), {64, 48});
        check_slots(cg);
        for (size_t i = 0; i < cg.passes.size(); ++i)
            for (const auto& [pin, b] : cg.passes[i].bindings) {
                const CompiledResource& r = cg.resources[b.resource];
                EXPECT_LE(r.writer, int(i));
                EXPECT_LE(r.first_use, int(i));
                EXPECT_GE(r.last_use, int(i));
            }
        EXPECT_EQ(cg.passes.size() + cg.culled.size(), size_t(n));
        if (cg.slots.size() < cg.resources.size()) ++pooled_some;
        if (HasFailure()) break;
    }
    EXPECT_GT(pooled_some, 50);  // the generator exercises sharing, not just separate slots
}
