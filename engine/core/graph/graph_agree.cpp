// Values that must agree, checked when the graph compiles (before any GL), each error naming
// both sides: the two ends of a parameter range (ParamOptions::at_most) and the parameters a
// pass shares with what produced an input that asks for them (PinOptions::same_params: MBOIT's
// two rasters, MLAB's bucket and blend, an OIT pass and its opaque core, LineAO and volume AO
// and their G-buffer, the legend and the lines). Pass types declare what must agree; nothing
// here knows a pass type by name.
#include "graph_internal.hpp"

#include <cmath>
#include <cstdint>
#include <set>

namespace pathlet::graph_detail {
namespace {

// A parameter's value in pass `p` as the compiler resolves it: written (a literal or a
// "$variable") or the default. Null where the written value is wrong (reported elsewhere).
json value_of(const GraphFile& g, const PassDecl& p, const ParamDecl& d) {
    if (!p.params.contains(d.name)) return d.def;
    json out;
    return resolve_param(g, d, p.params.at(d.name), out).empty() ? out : json();
}

std::string shown(const json& v) {
    if (v.is_string()) return v.get<std::string>();
    if (v.is_number() && v.get<double>() == std::floor(v.get<double>()) && std::fabs(v.get<double>()) < 1e15)
        return std::to_string(int64_t(v.get<double>()));  // 8, not 8.0
    return v.dump();
}

// Where an error about parameter `name` of pass `p` points: at the value if written.
std::string where(const PassDecl& p, const std::string& name) {
    return p.params.contains(name) ? p.pointer + "/params/" + pointer_escape(name) : p.pointer;
}

void check_ranges(const GraphFile& g, const PassDecl& p, const PassTypeInfo& t, std::vector<Diagnostic>& diags) {
    for (const ParamDecl& lo : t.params) {
        const ParamDecl* hi = lo.at_most.empty() ? nullptr : t.param(lo.at_most);
        if (!hi) continue;
        const json a = value_of(g, p, lo), b = value_of(g, p, *hi);
        if (!a.is_number() || !b.is_number()) continue;
        const double x = a.get<double>(), y = b.get<double>();
        // An automatic end (the lower end's option speaks for the range) is not compared.
        if (x <= lo.automatic_at_or_below || y <= lo.automatic_at_or_below || x <= y) continue;
        diags.push_back({g.path, where(p, p.params.contains(lo.name) ? lo.name : hi->name),
                         "pass '" + p.name + "': " + lo.name + " = " + shown(a) + " is above " + hi->name + " = " +
                             shown(b) + "; " + lo.name + " must not exceed " + hi->name});
    }
}

// The nearest pass up the chain of writers from resource `r` (breadth first) that declares a
// parameter `name` of type `type`, or -1.
int nearest_declaring(const GraphIndex& idx, int r, size_t reader, const std::string& name, ParamType type) {
    std::vector<int> queue = {idx.writer(r)};
    std::set<int> seen;
    for (size_t k = 0; k < queue.size(); ++k) {
        const int w = queue[k];
        if (w < 0 || w == int(reader) || !seen.insert(w).second || !idx.types[size_t(w)]) continue;
        if (const ParamDecl* d = idx.types[size_t(w)]->param(name); d && d->type == type) return w;
        for (const BoundPin& in : idx.inputs[size_t(w)])
            if (in.resource >= 0 && !in.prev) queue.push_back(idx.writer(in.resource));
    }
    return -1;
}

void check_upstream(const GraphIndex& idx, size_t i, std::vector<Diagnostic>& diags) {
    const GraphFile& g = *idx.g;
    const PassDecl& p = g.passes[i];
    const PassTypeInfo& t = *idx.types[i];
    std::set<std::pair<std::string, int>> reported;  // several pins may lead to one pass
    for (const BoundPin& b : idx.inputs[i]) {
        if (!b.decl || b.decl->same_params.empty() || b.resource < 0 || b.prev) continue;
        std::vector<std::string> names = b.decl->same_params;
        if (names == std::vector<std::string>{"*"}) {
            names.clear();
            for (const ParamDecl& d : t.params) names.push_back(d.name);
        }
        for (const std::string& name : names) {
            const ParamDecl* d = t.param(name);
            const int w = d ? nearest_declaring(idx, b.resource, i, name, d->type) : -1;
            if (w < 0 || reported.count({name, w})) continue;
            const PassDecl& wp = g.passes[size_t(w)];
            const json mine = value_of(g, p, *d), theirs = value_of(g, wp, *idx.types[size_t(w)]->param(name));
            if (mine.is_null() || theirs.is_null() || mine == theirs) continue;
            reported.insert({name, w});
            diags.push_back({g.path, where(p, name),
                             "pass '" + p.name + "' (" + t.type + ") has " + name + " = " + shown(mine) +
                                 " but pass '" + wp.name + "' (" + idx.types[size_t(w)]->type + "), which its input '" +
                                 b.pin + "' comes from, has " + name + " = " + shown(theirs) +
                                 ": the two must agree (give both the same value, e.g. through a graph variable)"});
        }
    }
}

}  // namespace

void check_agreement(const GraphIndex& idx, std::vector<Diagnostic>& diags) {
    for (size_t i = 0; i < idx.g->passes.size(); ++i) {
        if (!idx.types[i]) continue;  // unknown type: reported elsewhere
        check_ranges(*idx.g, idx.g->passes[i], *idx.types[i], diags);
        check_upstream(idx, i, diags);
    }
}

}  // namespace pathlet::graph_detail
