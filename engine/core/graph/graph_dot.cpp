// graph_to_dot: Graphviz view of a compiled graph. Passes are boxes, resources ellipses;
// culled passes are grey and dashed with the reason as tooltip; history reads are dashed edges.
#include "graph_internal.hpp"

#include <algorithm>
#include <set>
#include <sstream>

namespace pathlet {

using namespace graph_detail;

namespace {

std::string esc(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out;
}

std::string pass_node(const std::string& n) { return "\"pass:" + esc(n) + "\""; }
std::string res_node(const std::string& n) { return "\"res:" + esc(n) + "\""; }

}  // namespace

std::string graph_to_dot(const CompiledGraph& cg, const GraphFile& g) {
    std::ostringstream s;
    s << "digraph \"" << esc(cg.name.empty() ? cg.file : cg.name) << "\" {\n"
      << "  rankdir=LR;\n  node [fontname=\"Helvetica\", fontsize=10];\n  edge [fontname=\"Helvetica\", fontsize=9];\n";

    for (const auto& r : cg.resources) {
        std::string label = r.name + "\\n" +
                            (r.kind == PinKind::Buffer ? "buffer " + std::to_string(r.bytes) + " B"
                                                       : r.format + " " + std::to_string(r.width) + "x" + std::to_string(r.height));
        if (r.history) label += "\\nhistory";
        if (r.slot >= 0) label += "\\nslot " + std::to_string(r.slot);
        s << "  " << res_node(r.name) << " [shape=ellipse, label=\"" << esc(label) << "\"" << (r.captured ? ", peripheries=2" : "")
          << "];\n";
    }
    for (const auto& p : cg.passes) {
        s << "  " << pass_node(p.name) << " [shape=box, label=\"" << esc(p.name) << "\\n(" << esc(p.type->type) << ")\"];\n";
        for (const auto& [pin, b] : p.bindings) {
            const PinDecl* d = p.type->pin(pin);
            const std::string res = res_node(cg.resources[b.resource].name);
            if (d && d->dir == PinDir::Output) s << "  " << pass_node(p.name) << " -> " << res << " [label=\"" << esc(pin) << "\"];\n";
            else if (b.previous)
                s << "  " << res << " -> " << pass_node(p.name) << " [style=dashed, label=\"" << esc(pin) << " (@prev)\"];\n";
            else s << "  " << res << " -> " << pass_node(p.name) << " [label=\"" << esc(pin) << "\"];\n";
        }
    }

    // Culled passes, wired by name from the file: a "pass.pin" reference to a bound output
    // becomes the resource it names; anything not compiled is drawn grey.
    std::set<std::string> drawn;
    for (const auto& r : cg.resources) drawn.insert(r.name);
    auto culled_res = [&](const std::string& name) {
        if (drawn.insert(name).second)
            s << "  " << res_node(name) << " [shape=ellipse, style=dashed, color=grey, fontcolor=grey, label=\"" << esc(name)
              << "\"];\n";
        return res_node(name);
    };
    for (const auto& c : cg.culled) {
        s << "  " << pass_node(c.name) << " [shape=box, style=dashed, color=grey, fontcolor=grey, label=\"" << esc(c.name)
          << "\\n(culled)\", tooltip=\"" << esc(c.reason) << "\"];\n";
        auto decl = std::find_if(g.passes.begin(), g.passes.end(), [&](const auto& p) { return p.name == c.name; });
        if (decl == g.passes.end()) continue;
        for (const auto& [pin, ref] : decl->inputs) {
            Ref r = split_ref(ref);
            std::string name = r.name;
            if (size_t dot = name.find('.'); dot != std::string::npos) {
                auto w = std::find_if(g.passes.begin(), g.passes.end(), [&](const auto& p) { return p.name == name.substr(0, dot); });
                if (w != g.passes.end() && w->outputs.count(name.substr(dot + 1))) name = w->outputs.at(name.substr(dot + 1));
            }
            s << "  " << culled_res(name) << " -> " << pass_node(c.name) << " [color=grey, " << (r.prev ? "style=dashed, " : "")
              << "label=\"" << esc(pin) << (r.prev ? " (@prev)" : "") << "\"];\n";
        }
        for (const auto& [pin, res] : decl->outputs)
            s << "  " << pass_node(c.name) << " -> " << culled_res(res) << " [color=grey, label=\"" << esc(pin) << "\"];\n";
    }
    s << "}\n";
    return s.str();
}

}  // namespace pathlet
