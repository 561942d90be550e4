// plan_to_text / plan_to_json: the compiled plan for `pathlet graph --plan` and tools: execution
// order with pins, culled passes, lifetimes, slot assignment, memory before/after pooling.
#include "graph_internal.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace pathlet {

using namespace graph_detail;

namespace {

std::string mib(size_t bytes) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f MiB", double(bytes) / (1024.0 * 1024.0));
    return buf;
}

std::string pad(const std::string& s, size_t n) { return s.size() >= n ? s : s + std::string(n - s.size(), ' '); }

std::string describe(const CompiledResource& r) {
    if (r.kind == PinKind::Buffer) return "buffer " + std::to_string(r.bytes) + " B";
    return r.format + " " + std::to_string(r.width) + "x" + std::to_string(r.height) +
           (r.mips > 1 ? " " + std::to_string(r.mips) + " mips" : "");
}

std::string flags(const CompiledResource& r) {
    std::vector<std::string> f;
    if (r.history) f.push_back("history");
    if (r.persistent) f.push_back("persistent");
    if (r.captured) f.push_back("output");
    return f.empty() ? "transient" : join(f, ",");
}

// "|..####....|": one column per pass in execution order, '#' while the resource is alive.
std::string lifetime_chart(const CompiledResource& r, size_t passes) {
    std::string s = "|";
    for (size_t i = 0; i < passes; ++i) s += int(i) >= r.first_use && int(i) <= r.last_use ? '#' : '.';
    return s + "|";
}

}  // namespace

std::string plan_to_text(const CompiledGraph& cg) {
    std::ostringstream s;
    s << "graph '" << cg.name << "' (" << cg.file << "), output " << cg.output_size.x << "x" << cg.output_size.y << "\n";
    if (!cg.variables.empty()) {
        s << "variables:\n";
        for (const auto& [k, v] : cg.variables.items()) s << "  " << k << " = " << v.dump() << "\n";
    }
    s << "execution order (" << cg.passes.size() << " passes):\n";
    for (size_t i = 0; i < cg.passes.size(); ++i) {
        const CompiledPass& p = cg.passes[i];
        s << "  " << i << ". " << p.name << " [" << p.type->type << "]\n";
        for (const auto& h : p.hooks) s << "       hook " << h.param << " = " << h.name << ": " << h.file << "\n";
        for (const auto& [pin, b] : p.bindings) {
            const PinDecl* d = p.type->pin(pin);
            const bool out = d && d->dir == PinDir::Output;
            s << "       " << (out ? "out " : "in  ") << pin << (out ? " -> " : " <- ") << cg.resources[b.resource].name
              << (b.previous ? "@prev" : "") << "\n";
        }
    }
    if (!cg.culled.empty()) {
        s << "culled:\n";
        for (const auto& c : cg.culled) s << "  " << c.name << ": " << c.reason << "\n";
    }

    size_t w = 4;
    for (const auto& r : cg.resources) w = std::max(w, r.name.size());
    s << "resources (lifetimes over passes 0.." << (cg.passes.empty() ? 0 : cg.passes.size() - 1) << "):\n";
    for (const auto& r : cg.resources)
        s << "  " << pad(r.name, w) << "  " << lifetime_chart(r, cg.passes.size()) << "  slot " << pad(std::to_string(r.slot), 3)
          << " " << pad(describe(r), 28) << " " << pad(mib(allocated_bytes(r)), 12) << " " << flags(r) << "\n";
    s << "slots:\n";
    for (size_t i = 0; i < cg.slots.size(); ++i) {
        const PoolSlot& sl = cg.slots[i];
        std::vector<std::string> names;
        for (int r : sl.resources) names.push_back(cg.resources[r].name);
        s << "  slot " << i << ": " << mib(sl.bytes) << " <- " << join(names) << "\n";
    }
    const size_t saved = cg.memory_unpooled - std::min(cg.memory_unpooled, cg.memory_pooled);
    s << "memory: " << mib(cg.memory_unpooled) << " before pooling, " << mib(cg.memory_pooled) << " after pooling (saves "
      << mib(saved) << ", " << (cg.memory_unpooled ? 100 * saved / cg.memory_unpooled : 0) << "%)\n";
    return s.str();
}

json plan_to_json(const CompiledGraph& cg) {
    json j;
    j["file"] = cg.file;
    j["name"] = cg.name;
    j["output_size"] = {cg.output_size.x, cg.output_size.y};
    j["variables"] = cg.variables;
    j["passes"] = json::array();
    for (const auto& p : cg.passes) {
        json b = json::object();
        for (const auto& [pin, x] : p.bindings) {
            const PinDecl* d = p.type->pin(pin);
            b[pin] = {{"resource", cg.resources[x.resource].name},
                      {"dir", d && d->dir == PinDir::Output ? "output" : "input"},
                      {"previous", x.previous}};
        }
        json hooks = json::object();
        for (const auto& h : p.hooks) hooks[h.param] = {{"name", h.name}, {"file", h.file}};
        j["passes"].push_back({{"name", p.name}, {"type", p.type->type}, {"params", p.params}, {"bindings", b}, {"hooks", hooks}});
    }
    j["culled"] = json::array();
    for (const auto& c : cg.culled) j["culled"].push_back({{"name", c.name}, {"reason", c.reason}});
    j["resources"] = json::array();
    for (const auto& r : cg.resources) {
        json x = {{"name", r.name},
                  {"kind", r.kind == PinKind::Texture ? "texture" : "buffer"},
                  {"bytes", r.bytes},
                  {"allocated_bytes", allocated_bytes(r)},
                  {"history", r.history},
                  {"persistent", r.persistent},
                  {"captured", r.captured},
                  {"transient", r.transient()},
                  {"writer", r.writer >= 0 ? json(cg.passes[r.writer].name) : json(nullptr)},
                  {"first_use", r.first_use},
                  {"last_use", r.last_use},
                  {"slot", r.slot}};
        if (r.kind == PinKind::Texture) {
            x["format"] = r.format;
            x["width"] = r.width;
            x["height"] = r.height;
            x["mips"] = r.mips;
        }
        j["resources"].push_back(x);
    }
    j["slots"] = json::array();
    for (const auto& s : cg.slots) {
        json names = json::array();
        for (int r : s.resources) names.push_back(cg.resources[r].name);
        json x = {{"kind", s.kind == PinKind::Texture ? "texture" : "buffer"}, {"bytes", s.bytes}, {"resources", names}};
        if (s.kind == PinKind::Texture) {
            const FormatInfo* f = find_format(s.internal_format);
            x["format"] = f ? f->name : "";
            x["width"] = s.width;
            x["height"] = s.height;
            x["mips"] = s.mips;
        }
        j["slots"].push_back(x);
    }
    j["outputs"] = json::array();
    for (const auto& o : cg.outputs) j["outputs"].push_back({{"resource", o.resource}, {"capture", o.capture}});
    j["memory"] = {{"unpooled", cg.memory_unpooled}, {"pooled", cg.memory_pooled}};
    return j;
}

}  // namespace pathlet
