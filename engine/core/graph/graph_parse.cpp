// Graph file parser: JSON (with // and /* */ comments) -> GraphFile. Checks structure only
// (keys, JSON types, names, formats, sizes); what names refer to is checked by validate_graph.
// The schema ships as graphs/schema/pathlet-graph.schema.json.
//
// {
//   "version": 1,                                   // optional; newer versions are refused
//   "name": "deferred", "description": "...",
//   "variables": {                                  // typed knobs, --set name=value
//     "radius": {"type": "float|int|bool|string|enum|vec3|color", "default": 0.5,
//                "min": 0, "max": 4,                // int/float only
//                "choices": ["a", "b"],             // enum only (required there)
//                "doc": "..."}
//   },
//   "resources": {
//     "hdr":  {"kind": "texture",                   // default "texture"; or "buffer"
//              "format": "rgba16f",                 // optional: else the writing pin's format
//              "size": "output" | [w, h] | {"relative_to": "output|<resource>", "scale": s | [sx, sy]},
//              "mips": 1 | "full",                  // optional: else the writing pin's
//              "history": false,                    // keep last frame's content: read "hdr@prev"
//              "persistent": false,                 // never pooled
//              "doc": "..."},
//     "list": {"kind": "buffer", "bytes": 65536 | "bytes_per_pixel": 8}
//   },
//   "passes": [
//     {"name": "ssao", "type": "ssao",
//      "params": {"radius": "$radius"},             // literals or "$variable"
//      "inputs": {"depth": "depth" | "gbuffer.depth" | "taa_out@prev"},
//      "outputs": {"ao": "ao"},                     // unbound outputs become "<pass>.<pin>"
//      "enabled": true | "$use_ssao",
//      "doc": "..."}
//   ],
//   "outputs": [{"resource": "ldr" | "tonemap.dst", "capture": "out/{graph}/{frame:05}.png"}]
// }
//
// Every problem is collected with its JSON pointer; one GraphError is thrown at the end.
#include "graph_internal.hpp"

#include <pathlet/scene.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>

namespace pathlet {

using namespace graph_detail;

namespace {

// Characters no name may hold, whatever it names: names become parts of file paths ({graph},
// {output}) and of messages printed on a terminal.
std::string unsafe_name_characters(const std::string& name, const std::string& what) {
    for (char c : name) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '/' || c == '\\') return what + " name '" + name + "' must not contain '/' or '\\' (it is part of file paths)";
        if (u < 0x20 || u == 0x7f) return what + " name must not contain control characters";
    }
    return "";
}

}  // namespace

std::string graph_name_problem(const std::string& name) {
    if (std::string why = unsafe_name_characters(name, "graph"); !why.empty()) return why;
    if (name == "." || name == "..")
        return "graph name '" + name + "' would name a folder, not one of its own ({graph} in output paths)";
    return "";
}

namespace {

class Parser {
public:
    explicit Parser(std::string file) : file_(std::move(file)) {}

    GraphFile parse(const json& root) {
        GraphFile g;
        g.path = file_;
        if (!root.is_object()) {
            error("", "a graph file must be a JSON object");
            return g;
        }
        check_keys(root, "",
                   {"$schema", "version", "name", "description", "plugin_dirs", "variables", "resources", "passes",
                    "outputs", "extends"},
                   "top-level key");
        if (const json* dirs = array_at(root, "plugin_dirs", "")) {
            const std::filesystem::path base = std::filesystem::path(file_).parent_path();
            for (size_t i = 0; i < dirs->size(); ++i) {
                const json& d = (*dirs)[i];
                if (!d.is_string() || d.get<std::string>().empty()) {
                    error("/plugin_dirs/" + std::to_string(i), "a plugin folder must be a non-empty string, got " + d.dump());
                    continue;
                }
                std::filesystem::path p = d.get<std::string>();
                g.plugin_dirs.push_back((p.is_absolute() ? p : base / p).lexically_normal().string());
            }
        }
        if (root.contains("version")) {
            const json& v = root["version"];
            if (!v.is_number_integer() || v.get<int64_t>() < 1)
                error("/version", "version must be a positive integer, got " + v.dump());
            else if (v.get<int64_t>() > 1)
                error("/version", "version " + v.dump() + " is newer than this engine understands (1)");
            else
                g.version = 1;
        }
        g.name = string_at(root, "name", "", "");
        if (std::string why = graph_name_problem(g.name); !g.name.empty() && !why.empty()) error("/name", why);
        g.description = string_at(root, "description", "", "");
        if (const json* vars = object_at(root, "variables", ""))
            for (const auto& [k, v] : vars->items()) parse_variable(g, k, v);
        if (const json* res = object_at(root, "resources", ""))
            for (const auto& [k, v] : res->items()) parse_resource(g, k, v);
        if (const json* passes = array_at(root, "passes", ""))
            for (size_t i = 0; i < passes->size(); ++i) parse_pass(g, i, (*passes)[i]);
        if (const json* outs = array_at(root, "outputs", ""))
            for (size_t i = 0; i < outs->size(); ++i) parse_output(g, i, (*outs)[i]);
        return g;
    }

    std::vector<Diagnostic> diags;

private:
    std::string file_;

    void error(const std::string& ptr, const std::string& msg) { diags.push_back({file_, ptr, msg}); }

    void check_keys(const json& obj, const std::string& ptr, const std::vector<std::string>& allowed,
                    const std::string& what) {
        for (const auto& [k, v] : obj.items())
            if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
                error(ptr + "/" + pointer_escape(k),
                      "unknown " + what + " '" + k + "'" + did_you_mean(k, allowed) + "; allowed: " + join(allowed));
    }

    const json* typed_at(const json& obj, const char* key, const std::string& ptr, bool (json::*is)() const noexcept,
                         const char* what) {
        auto it = obj.find(key);
        if (it == obj.end()) return nullptr;
        if (!((*it).*is)()) {
            error(ptr + "/" + key, std::string("'") + key + "' must be " + what + ", got " + it->dump());
            return nullptr;
        }
        return &*it;
    }
    const json* object_at(const json& o, const char* k, const std::string& p) {
        return typed_at(o, k, p, &json::is_object, "an object");
    }
    const json* array_at(const json& o, const char* k, const std::string& p) {
        return typed_at(o, k, p, &json::is_array, "an array");
    }
    std::string string_at(const json& o, const char* k, const std::string& p, const std::string& def) {
        const json* v = typed_at(o, k, p, &json::is_string, "a string");
        return v ? v->get<std::string>() : def;
    }
    bool bool_at(const json& o, const char* k, const std::string& p, bool def) {
        const json* v = typed_at(o, k, p, &json::is_boolean, "true or false");
        return v ? v->get<bool>() : def;
    }
    // Non-negative integer; -1 when absent or bad.
    int64_t count_at(const json& o, const char* k, const std::string& p) {
        auto it = o.find(k);
        if (it == o.end()) return -1;
        if (!it->is_number_integer() || it->get<int64_t>() < 0) {
            error(p + "/" + k, std::string("'") + k + "' must be a non-negative integer, got " + it->dump());
            return -1;
        }
        return it->get<int64_t>();
    }

    // Resource and pass names appear in references ("pass.pin", "res@prev", "$var"), so those
    // characters are reserved.
    void check_name(const std::string& name, const std::string& ptr, const char* what) {
        if (name.empty()) {
            error(ptr, std::string(what) + " name must not be empty");
            return;
        }
        for (char c : name)
            if (c == '.' || c == '@' || c == '$' || c == '=' || std::isspace(static_cast<unsigned char>(c))) {
                error(ptr, std::string(what) + " name '" + name + "' must not contain '.', '@', '$', '=' or spaces");
                return;
            }
        if (std::string why = unsafe_name_characters(name, what); !why.empty()) error(ptr, why);
    }

    // A variable whose declaration is wrong (reported) stays, without a value: what uses it is
    // checked for everything else (parse_graph_file with diagnostics: validate's every error).
    void keep_broken(GraphFile& g, VariableDecl var) {
        var.value = nullptr;
        g.variables.push_back(std::move(var));
    }

    void parse_variable(GraphFile& g, const std::string& name, const json& v) {
        const std::string ptr = "/variables/" + pointer_escape(name);
        check_name(name, ptr, "variable");
        if (!v.is_object()) {
            error(ptr, "a variable must be an object with \"type\" and \"default\", got " + v.dump());
            return;
        }
        check_keys(v, ptr, {"type", "default", "min", "max", "choices", "doc"}, "variable key");
        static const std::vector<std::pair<std::string, ParamType>> types = {
            {"float", ParamType::Float}, {"int", ParamType::Int},   {"bool", ParamType::Bool},
            {"string", ParamType::String}, {"enum", ParamType::Enum}, {"vec3", ParamType::Vec3},
            {"color", ParamType::Color}};
        VariableDecl var;
        var.name = name;
        var.pointer = ptr;
        var.decl.name = name;
        var.decl.doc = string_at(v, "doc", ptr, "");
        std::string type = string_at(v, "type", ptr, "");
        bool typed = false;
        std::vector<std::string> type_names;
        for (const auto& [n, t] : types) {
            type_names.push_back(n);
            if (n == type) var.decl.type = t, typed = true;
        }
        if (!typed) {
            error(ptr + "/type", v.contains("type") ? "unknown variable type '" + type + "'" + did_you_mean(type, type_names) +
                                                          "; one of " + join(type_names)
                                                    : "a variable needs a \"type\": one of " + join(type_names));
            return keep_broken(g, std::move(var));
        }
        const bool numeric = var.decl.type == ParamType::Int || var.decl.type == ParamType::Float;
        for (const char* k : {"min", "max"}) {
            if (!v.contains(k)) continue;
            if (!numeric) error(ptr + "/" + k, std::string("'") + k + "' applies to int and float variables only");
            else if (!v[k].is_number()) error(ptr + "/" + k, std::string("'") + k + "' must be a number");
            else (k[1] == 'i' ? var.decl.min : var.decl.max) = v[k].get<double>();
        }
        if (v.contains("choices")) {
            if (var.decl.type != ParamType::Enum) error(ptr + "/choices", "'choices' applies to enum variables only");
            else if (!v["choices"].is_array() || v["choices"].empty())
                error(ptr + "/choices", "'choices' must be a non-empty array of strings");
            else
                for (const auto& c : v["choices"]) {
                    if (c.is_string()) var.decl.choices.push_back(c.get<std::string>());
                    else error(ptr + "/choices", "'choices' must hold strings, got " + c.dump());
                }
        } else if (var.decl.type == ParamType::Enum) {
            error(ptr, "an enum variable needs \"choices\"");
            return keep_broken(g, std::move(var));
        }
        if (!v.contains("default")) {
            error(ptr, "a variable needs a \"default\"");
            return keep_broken(g, std::move(var));
        }
        std::string err = var.decl.coerce(v["default"], var.value);
        if (!err.empty()) {
            error(ptr + "/default", "default of variable '" + name + "' " + err);
            return keep_broken(g, std::move(var));
        }
        var.decl.def = var.value;
        g.variables.push_back(std::move(var));
    }

    std::optional<SizeDecl> parse_size(const json& s, const std::string& ptr) {
        SizeDecl d;
        if (s.is_string()) {
            if (s.get<std::string>() == "output") return d;
            error(ptr, "size must be \"output\", [w, h] or {\"relative_to\": ..., \"scale\": ...}; for another resource use "
                       "{\"relative_to\": " + s.dump() + "}");
            return std::nullopt;
        }
        if (s.is_array()) {
            if (s.size() != 2 || !s[0].is_number_integer() || !s[1].is_number_integer() || s[0].get<int64_t>() < 1 ||
                s[1].get<int64_t>() < 1 || s[0].get<int64_t>() > 65536 || s[1].get<int64_t>() > 65536) {
                error(ptr, "an absolute size must be [width, height] with positive integers, got " + s.dump());
                return std::nullopt;
            }
            d.relative_to = "";
            d.width = int(s[0].get<int64_t>());
            d.height = int(s[1].get<int64_t>());
            return d;
        }
        if (!s.is_object()) {
            error(ptr, "size must be \"output\", [w, h] or {\"relative_to\": ..., \"scale\": ...}, got " + s.dump());
            return std::nullopt;
        }
        check_keys(s, ptr, {"relative_to", "scale"}, "size key");
        d.relative_to = string_at(s, "relative_to", ptr, "output");
        if (d.relative_to.empty()) error(ptr + "/relative_to", "relative_to must name \"output\" or a resource");
        if (s.contains("scale")) {
            const json& sc = s["scale"];
            // Capped well below float's range: the scale is stored as float.
            auto positive = [](const json& x) { return x.is_number() && x.get<double>() > 0 && x.get<double>() <= 1e6; };
            if (positive(sc)) {
                d.scale_x = d.scale_y = sc.get<float>();
            } else if (sc.is_array() && sc.size() == 2 && positive(sc[0]) && positive(sc[1])) {
                d.scale_x = sc[0].get<float>();
                d.scale_y = sc[1].get<float>();
            } else {
                error(ptr + "/scale", "scale must be a positive number (at most 1e6) or [sx, sy] of such numbers, got " + sc.dump());
                return std::nullopt;
            }
        }
        return d;
    }

    void parse_resource(GraphFile& g, const std::string& name, const json& v) {
        const std::string ptr = "/resources/" + pointer_escape(name);
        check_name(name, ptr, "resource");
        if (!v.is_object()) {
            error(ptr, "a resource must be an object, got " + v.dump());
            return;
        }
        check_keys(v, ptr, {"kind", "format", "size", "mips", "bytes", "bytes_per_pixel", "history", "persistent", "doc"},
                   "resource key");
        ResourceDecl r;
        r.name = name;
        r.pointer = ptr;
        std::string kind = string_at(v, "kind", ptr, "texture");
        if (kind == "buffer") r.kind = PinKind::Buffer;
        else if (kind != "texture")
            error(ptr + "/kind", "unknown resource kind '" + kind + "'" + did_you_mean(kind, {"texture", "buffer"}) +
                                     "; one of texture, buffer");
        const bool tex = r.kind == PinKind::Texture;
        auto texture_only = [&](const char* k) {
            if (!tex && v.contains(k)) error(ptr + "/" + k, std::string("'") + k + "' applies to textures, not buffers");
        };
        auto buffer_only = [&](const char* k) {
            if (tex && v.contains(k))
                error(ptr + "/" + k, std::string("'") + k + "' applies to buffers; add \"kind\": \"buffer\"");
        };
        texture_only("format");
        texture_only("size");
        texture_only("mips");
        buffer_only("bytes");
        buffer_only("bytes_per_pixel");
        if (tex && v.contains("format")) {
            r.format = string_at(v, "format", ptr, "");
            if (v["format"].is_string() && !find_format(r.format))
                error(ptr + "/format", "unknown format '" + r.format + "'" + did_you_mean(r.format, format_names()) +
                                           "; one of " + join(format_names()));
        }
        if (tex && v.contains("size")) r.size = parse_size(v["size"], ptr + "/size");
        if (tex && v.contains("mips")) {
            const json& m = v["mips"];
            if (m.is_string() && m.get<std::string>() == "full") r.mips = 0;
            else if (m.is_number_integer() && m.get<int64_t>() >= 1 && m.get<int64_t>() <= 16) r.mips = int(m.get<int64_t>());
            else error(ptr + "/mips", "mips must be an integer 1..16 or \"full\", got " + m.dump());
        }
        if (!tex) {
            int64_t b = count_at(v, "bytes", ptr), bpp = count_at(v, "bytes_per_pixel", ptr);
            if (b > 0) r.bytes = size_t(b);
            if (bpp > 0) r.bytes_per_pixel = size_t(bpp);
            if (b > 0 && bpp > 0) error(ptr, "give either \"bytes\" or \"bytes_per_pixel\", not both");
        }
        r.history = bool_at(v, "history", ptr, false);
        r.persistent = bool_at(v, "persistent", ptr, false);
        string_at(v, "doc", ptr, "");
        g.resources.push_back(std::move(r));
    }

    void parse_bindings(const json& v, const char* key, const std::string& ptr, std::map<std::string, std::string>& out) {
        const json* m = object_at(v, key, ptr);
        if (!m) return;
        for (const auto& [pin, ref] : m->items()) {
            if (ref.is_string() && !ref.get<std::string>().empty()) out[pin] = ref.get<std::string>();
            else
                error(ptr + "/" + key + "/" + pointer_escape(pin),
                      std::string(key) == "inputs" ? "an input must name \"resource\", \"pass.pin\" or \"resource@prev\", got " + ref.dump()
                                                   : "an output must name a resource, got " + ref.dump());
        }
    }

    void parse_pass(GraphFile& g, size_t i, const json& v) {
        const std::string ptr = "/passes/" + std::to_string(i);
        if (!v.is_object()) {
            error(ptr, "a pass must be an object with \"name\" and \"type\", got " + v.dump());
            return;
        }
        check_keys(v, ptr, {"name", "type", "params", "inputs", "outputs", "enabled", "doc"}, "pass key");
        PassDecl p;
        p.pointer = ptr;
        p.name = string_at(v, "name", ptr, "");
        p.type = string_at(v, "type", ptr, "");
        if (!v.contains("name")) error(ptr, "a pass needs a \"name\"");
        else check_name(p.name, ptr + "/name", "pass");
        if (!v.contains("type")) error(ptr, "a pass needs a \"type\"");
        if (const json* params = object_at(v, "params", ptr)) p.params = *params;
        parse_bindings(v, "inputs", ptr, p.inputs);
        parse_bindings(v, "outputs", ptr, p.outputs);
        if (v.contains("enabled")) {
            const json& e = v["enabled"];
            if (e.is_boolean() || is_variable_ref(e)) p.enabled = e;
            else error(ptr + "/enabled", "enabled must be true, false or \"$variable\", got " + e.dump());
        }
        string_at(v, "doc", ptr, "");
        g.passes.push_back(std::move(p));
    }

    void parse_output(GraphFile& g, size_t i, const json& v) {
        const std::string ptr = "/outputs/" + std::to_string(i);
        OutputDecl o;
        o.pointer = ptr;
        if (v.is_string()) {
            o.resource = v.get<std::string>();
        } else if (v.is_object()) {
            check_keys(v, ptr, {"resource", "capture"}, "output key");
            o.resource = string_at(v, "resource", ptr, "");
            o.capture = string_at(v, "capture", ptr, "");
            if (!v.contains("resource")) error(ptr, "an output needs a \"resource\"");
        } else {
            error(ptr, "an output must be {\"resource\": ..., \"capture\": ...} or a resource name, got " + v.dump());
            return;
        }
        g.outputs.push_back(std::move(o));
    }
};

}  // namespace

namespace {
// Sets the 1-based line and column of byte `offset` of `text` on a diagnostic.
Diagnostic placed(Diagnostic d, const std::string& text, size_t offset) {
    offset = std::min(offset, text.size());
    d.line = 1 + int(std::count(text.begin(), text.begin() + long(offset), '\n'));
    const size_t nl = offset == 0 ? std::string::npos : text.rfind('\n', offset - 1);
    d.column = int(offset - (nl == std::string::npos ? 0 : nl + 1)) + 1;
    return d;
}
}  // namespace

json graph_detail::graph_json_from_text(const std::string& text, const std::string& path) {
    // text::parse_json refuses nesting beyond io::max_json_depth() before parsing: a value
    // nested 100k deep would overflow the stack when it is copied or printed in a message.
    try {
        return text::parse_json(text);
    } catch (const text::JsonError& e) {
        Diagnostic d{path, "", e.what()};
        throw GraphError({e.offset == std::string::npos ? d : placed(d, text, e.offset)});
    }
}

json graph_detail::read_graph_json(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw GraphError({{path, "", "is a directory, not a graph file (give a .json file, e.g. " + path + "/*.json)"}});
    std::string bytes;
    try {
        bytes = text::read_json_text(path, "graph file");
    } catch (const DataError& e) {
        const std::string what = e.what();
        throw GraphError({{path, "", what.substr(std::min(what.size(), path.size() + 2))}});  // the file is in the diagnostic
    }
    return graph_json_from_text(bytes, path);
}

namespace {
// Merges the extends chain in, then parses the whole as one graph.
// With `diags`, problems of the document's parts go there and what could be read is returned;
// without, they are thrown (a JSON syntax error or a wrong "extends" is thrown either way).
GraphFile parse_root(json root, const std::string& path, std::vector<Diagnostic>* diags = nullptr) {
    std::vector<std::string> dirs, chain;
    LayerLog log;
    root = expand_extends(std::move(root), path, dirs, chain, &log);
    Parser p(path);
    GraphFile g = p.parse(root);
    if (!p.diags.empty() && !diags) throw GraphError(std::move(p.diags));
    if (diags) diags->insert(diags->end(), p.diags.begin(), p.diags.end());
    // No "name": the file's name (fade_v1.json is "fade_v1"), in titles, {graph} and the plan.
    if (g.name.empty()) {
        g.name = std::filesystem::path(path).stem().string();
        if (std::string why = graph_name_problem(g.name); !why.empty()) {
            Diagnostic d{path, "", why + " (the file's name; give the graph a \"name\")"};
            if (!diags) throw GraphError({d});
            diags->push_back(d);
        }
    }
    g.dirs = std::move(dirs);
    g.extends = std::move(chain);
    g.layers = log.layers;
    for (auto& pass : g.passes) {
        if (const auto it = log.written.find(pass.name); it != log.written.end()) pass.written = it->second;
        for (const auto& [name, swap] : log.swaps)
            if (name == pass.name) pass.swaps.push_back(swap);
    }
    return g;
}
}  // namespace

GraphFile parse_graph_json(const std::string& text, const std::string& path) {
    return parse_root(graph_json_from_text(text, path), path);
}

json expanded_graph_json(const std::string& path) {
    std::vector<std::string> dirs, chain;
    return expand_extends(read_graph_json(path), path, dirs, chain);
}

GraphFile parse_graph_file(const std::string& path) { return parse_root(read_graph_json(path), path); }

GraphFile parse_graph_file(const std::string& path, std::vector<Diagnostic>& diags) {
    return parse_root(read_graph_json(path), path, &diags);
}

}  // namespace pathlet
