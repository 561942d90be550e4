#include <pathlet/pass.hpp>

#include <pathlet/text.hpp>

#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace pathlet {

const char* direction_name(const PinDecl& p) { return p.internal ? "internal" : p.dir == PinDir::Input ? "in" : "out"; }

std::string binding_define(const std::string& pin) {
    std::string d;
    for (char c : pin) d += std::isalnum(static_cast<unsigned char>(c)) ? char(std::toupper(static_cast<unsigned char>(c))) : '_';
    return d + "_BINDING";
}

const char* to_string(ParamType t) {
    switch (t) {
        case ParamType::Bool: return "bool";
        case ParamType::Int: return "int";
        case ParamType::Float: return "float";
        case ParamType::String: return "string";
        case ParamType::Enum: return "enum";
        case ParamType::Vec3: return "vec3";
        case ParamType::Color: return "color";
    }
    return "?";
}

namespace {

std::string range_text(const ParamDecl& d) {
    std::ostringstream s;
    s << "[" << d.min << ", " << d.max << "]";
    return s.str();
}

using text::join;

// "#rrggbb" -> [r,g,b] in 0..1
bool parse_hex_color(const std::string& s, json& out) {
    if (s.size() != 7 || s[0] != '#') return false;
    unsigned v = 0;
    for (size_t i = 1; i < 7; ++i) {
        char c = s[i];
        int d = (c >= '0' && c <= '9') ? c - '0' : (c >= 'a' && c <= 'f') ? c - 'a' + 10 : (c >= 'A' && c <= 'F') ? c - 'A' + 10 : -1;
        if (d < 0) return false;
        v = v * 16 + unsigned(d);
    }
    out = json::array({((v >> 16) & 255) / 255.0, ((v >> 8) & 255) / 255.0, (v & 255) / 255.0});
    return true;
}

}  // namespace

std::string ParamDecl::coerce(const json& in, json& out) const {
    switch (type) {
        case ParamType::Bool:
            if (!in.is_boolean()) return "expects a bool (true/false), got " + in.dump();
            out = in;
            return "";
        case ParamType::Int: {
            if (!in.is_number_integer() && !(in.is_number_float() && std::floor(in.get<double>()) == in.get<double>()))
                return "expects an integer, got " + in.dump();
            double v = in.get<double>();
            if (v < min || v > max) return "value " + in.dump() + " is out of range " + range_text(*this);
            // Beyond +-2^63 the cast below is undefined; int parameters never need that much.
            if (std::fabs(v) >= 9.2e18) return "value " + in.dump() + " does not fit a 64-bit integer";
            out = static_cast<int64_t>(v);
            return "";
        }
        case ParamType::Float: {
            if (!in.is_number()) return "expects a number, got " + in.dump();
            double v = in.get<double>();
            if (!std::isfinite(v)) return "expects a finite number";
            if (v < min || v > max) return "value " + in.dump() + " is out of range " + range_text(*this);
            out = v;
            return "";
        }
        case ParamType::String:
            if (!in.is_string()) return "expects a string, got " + in.dump();
            out = in;
            return "";
        case ParamType::Enum: {
            if (!in.is_string()) return "expects one of " + join(choices) + ", got " + in.dump();
            for (const auto& c : choices)
                if (c == in.get<std::string>()) {
                    out = in;
                    return "";
                }
            return "'" + in.get<std::string>() + "' is not one of " + join(choices);
        }
        case ParamType::Vec3:
        case ParamType::Color: {
            if (type == ParamType::Color && in.is_string()) {
                if (parse_hex_color(in.get<std::string>(), out)) return "";
                return "expects a colour as [r,g,b] in 0..1 or \"#rrggbb\", got " + in.dump();
            }
            if (!in.is_array() || in.size() != 3) return "expects an array of 3 numbers, got " + in.dump();
            for (const auto& e : in)
                if (!e.is_number()) return "expects an array of 3 numbers, got " + in.dump();
            if (type == ParamType::Color)
                for (const auto& e : in)
                    if (e.get<double>() < 0.0 || e.get<double>() > 1.0) return "colour components must be in 0..1";
            out = json::array({in[0].get<double>(), in[1].get<double>(), in[2].get<double>()});
            return "";
        }
    }
    return "unknown parameter type";
}

std::string ParamDecl::coerce_text(const std::string& text, json& out) const {
    json in;
    switch (type) {
        case ParamType::String:
        case ParamType::Enum: in = text; break;
        case ParamType::Color:
            if (!text.empty() && text[0] == '#') {
                in = text;
                break;
            }
            [[fallthrough]];
        default:
            in = json::parse(text, nullptr, false);
            if (in.is_discarded()) {
                // allow "1,0,0" for vectors
                in = json::parse("[" + text + "]", nullptr, false);
                if (in.is_discarded() || (type != ParamType::Vec3 && type != ParamType::Color))
                    return "cannot read '" + text + "' as " + to_string(type);
            }
    }
    return coerce(in, out);
}

const ParamDecl* PassTypeInfo::param(const std::string& name) const {
    for (const auto& p : params)
        if (p.name == name) return &p;
    return nullptr;
}

const PinDecl* PassTypeInfo::pin(const std::string& name) const {
    for (const auto& p : pins)
        if (p.name == name) return &p;
    return nullptr;
}

json PassTypeInfo::default_params() const {
    json j = json::object();
    for (const auto& p : params) j[p.name] = p.def;
    return j;
}

namespace {
std::string md_pin_shape(const PinDecl& p);
}

std::string PassTypeInfo::describe() const {
    std::ostringstream s;
    s << type << " — " << doc << "\n";
    if (!plugin_file.empty()) s << "plugin: " << plugin_file << "\n";
    if (!gpu_wait_reason.empty())
        s << "waits for the GPU in the frame loop" << (gpu_wait_when.empty() ? "" : " (with " + gpu_wait_when + ")")
          << ": " << gpu_wait_reason << "\n";
    s << "\nparameters:\n";
    if (params.empty()) s << "  (none)\n";
    for (const auto& p : params) {
        s << "  " << p.name << " (" << to_string(p.type) << ", default " << p.def.dump();
        if (p.type == ParamType::Int || p.type == ParamType::Float)
            if (std::isfinite(p.min) || std::isfinite(p.max)) s << ", range " << range_text(p);
        if (p.type == ParamType::Enum) s << ", one of " << join(p.choices);
        if (p.pixels) s << ", pixels";
        if (p.hook) s << ", " << hook_role(*p.hook).name << " hook file";
        if (!p.origin.empty()) s << ", from " << p.origin.substr(0, p.origin.rfind(':'));
        s << ")\n      " << p.doc << "\n";
    }
    s << "\ninputs:\n";
    bool any = false;
    for (const auto& p : pins)
        if (p.dir == PinDir::Input) {
            any = true;
            s << "  " << p.name << " (" << (p.kind == PinKind::Texture ? "texture " + p.format : std::string("buffer"))
              << (p.optional ? ", optional" : "") << ")\n      " << p.doc << "\n";
        }
    if (!any) s << "  (none)\n";
    s << "\noutputs:\n";
    any = false;
    for (const auto& p : pins)
        if (p.dir == PinDir::Output && !p.internal) {
            any = true;
            s << "  " << p.name << " (";
            if (p.kind == PinKind::Texture) {
                s << "texture " << p.format;
                if (p.scale != 1.0f) s << ", " << p.scale << "x output size";
                if (p.mips != 1) s << ", " << (p.mips == 0 ? std::string("full mip chain") : std::to_string(p.mips) + " mips");
                if (p.optional) s << ", optional: written only when connected";
            } else {
                s << "buffer, ";
                if (p.bytes_from_params) s << "size from the parameters";
                if (p.bytes) s << p.bytes << " bytes";
                if (p.bytes_per_pixel) s << p.bytes_per_pixel << " bytes per output pixel";
                if (p.optional) s << ", optional: written only when connected";
            }
            s << ")\n      " << p.doc << "\n";
        }
    if (!any) s << "  (none)\n";
    any = false;
    for (const auto& p : pins)
        if (p.internal) {
            if (!any) s << "\ninternal (the pass's own textures and buffers: allocated by the engine, not bound in graphs):\n";
            any = true;
            s << "  " << p.name << " (";
            if (p.kind == PinKind::Texture) {
                s << "texture " << p.format;
                if (p.scale != 1.0f) s << ", " << p.scale << "x output size";
            } else {
                s << md_pin_shape(p);
            }
            if (p.persistent) s << ", kept across frames";
            s << ")\n      " << p.doc << "\n";
        }
    return s.str();
}

namespace {
std::string md_cell(std::string s) {  // a table cell: no pipes, no newlines
    for (char& c : s)
        if (c == '\n') c = ' ';
    std::string out;
    for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}
std::string md_pin_shape(const PinDecl& p) {
    if (p.kind == PinKind::Buffer)
        return "buffer" + (p.bytes_from_params ? std::string(", sized by parameters") : std::string()) +
               (p.bytes ? ", " + std::to_string(p.bytes) + " B" : std::string()) +
               (p.bytes_per_pixel ? ", " + std::to_string(p.bytes_per_pixel) + " B/pixel" : std::string());
    std::string s = p.format;
    if (p.mips != 1) s += p.mips == 0 ? ", mips" : ", " + std::to_string(p.mips) + " mips";
    if (p.scale != 1.0f) {
        std::ostringstream k;
        k << p.scale;
        s += ", " + k.str() + "x";
    }
    return s;
}
}  // namespace

std::string PassTypeInfo::markdown() const {
    std::ostringstream s;
    s << "| parameter | type | default | range | meaning |\n|---|---|---|---|---|\n";
    for (const auto& p : params) {
        std::string range;
        if ((p.type == ParamType::Int || p.type == ParamType::Float) && (std::isfinite(p.min) || std::isfinite(p.max)))
            range = range_text(p);
        if (p.type == ParamType::Enum) range = join(p.choices);
        if (p.pixels) range += range.empty() ? "pixels" : ", pixels";
        std::string doc = p.doc;
        if (p.hook) doc += std::string(" (") + hook_role(*p.hook).name + " hook file: its @param uniforms are parameters too)";
        if (!p.origin.empty()) doc += " (`" + p.origin.substr(0, p.origin.rfind(':')) + "`)";
        s << "| `" << p.name << "` | " << to_string(p.type) << " | `" << md_cell(p.def.dump()) << "` | " << md_cell(range)
          << " | " << md_cell(doc) << " |\n";
    }
    if (params.empty()) s << "| (none) | | | | |\n";
    s << "\n| pin | direction | kind, format | meaning |\n|---|---|---|---|\n";
    for (const auto& p : pins)
        s << "| `" << p.name << "` | " << direction_name(p)
          << (p.optional ? " (optional)" : "")
          << " | " << md_pin_shape(p) << " | " << md_cell(p.doc) << " |\n";
    return s.str();
}

std::string index_markdown(const std::vector<const PassTypeInfo*>& types) {
    std::ostringstream s;
    s << "| pass | what it does | inputs | outputs |\n|---|---|---|---|\n";
    for (const PassTypeInfo* t : types) {
        std::vector<std::string> in, out;
        for (const auto& p : t->pins)
            if (!p.internal) (p.dir == PinDir::Input ? in : out).push_back("`" + p.name + "`" + (p.optional ? "?" : ""));
        s << "| [`" << t->type << "`](" << t->type << "/README.md) | " << md_cell(t->doc) << " | "
          << (in.empty() ? "" : join(in)) << " | " << join(out) << " |\n";
    }
    s << "\n`?`: optional (a graph may leave it unbound).\n";
    return s.str();
}

PassTypeBuilder::PassTypeBuilder(std::string type, std::string doc) {
    info_.type = std::move(type);
    info_.doc = std::move(doc);
}

namespace {
ParamDecl make_param(const std::string& name, ParamType t, json def, const std::string& doc) {
    ParamDecl p;
    p.name = name;
    p.type = t;
    p.def = std::move(def);
    p.doc = doc;
    return p;
}
// An int or float parameter's range and options.
ParamDecl ranged(ParamDecl p, double min, double max, ParamOptions o) {
    p.min = min;
    p.max = max;
    p.pixels = o.pixels;
    p.at_most = o.at_most;
    p.automatic_at_or_below = o.automatic_at_or_below;
    return p;
}
}  // namespace

PassTypeBuilder& PassTypeBuilder::param_bool(const std::string& name, bool def, const std::string& doc) {
    info_.params.push_back(make_param(name, ParamType::Bool, def, doc));
    return *this;
}
PassTypeBuilder& PassTypeBuilder::param_int(const std::string& name, int def, int min, int max, const std::string& doc,
                                            ParamOptions o) {
    return param(ranged(make_param(name, ParamType::Int, def, doc), min, max, o));
}
PassTypeBuilder& PassTypeBuilder::param_float(const std::string& name, double def, double min, double max,
                                              const std::string& doc, ParamOptions o) {
    return param(ranged(make_param(name, ParamType::Float, def, doc), min, max, o));
}
PassTypeBuilder& PassTypeBuilder::param(ParamDecl d) {
    info_.params.push_back(std::move(d));
    return *this;
}
PassTypeBuilder& PassTypeBuilder::param_enum(const std::string& name, const std::string& def,
                                             std::vector<std::string> choices, const std::string& doc) {
    auto p = make_param(name, ParamType::Enum, def, doc);
    p.choices = std::move(choices);
    info_.params.push_back(p);
    return *this;
}
PassTypeBuilder& PassTypeBuilder::param_string(const std::string& name, const std::string& def, const std::string& doc) {
    info_.params.push_back(make_param(name, ParamType::String, def, doc));
    return *this;
}
PassTypeBuilder& PassTypeBuilder::param_hook(HookRole role, const std::string& def, const std::string& doc) {
    ParamDecl p = make_param(hook_role(role).param, ParamType::String, def, doc);
    p.hook = role;
    info_.params.push_back(p);
    return *this;
}
PassTypeBuilder& PassTypeBuilder::param_vec3(const std::string& name, glm::vec3 def, const std::string& doc) {
    info_.params.push_back(make_param(name, ParamType::Vec3, json::array({def.x, def.y, def.z}), doc));
    return *this;
}
PassTypeBuilder& PassTypeBuilder::param_color(const std::string& name, glm::vec3 def, const std::string& doc) {
    auto p = make_param(name, ParamType::Color, json::array({def.x, def.y, def.z}), doc);
    info_.params.push_back(p);
    return *this;
}

namespace {
PinDecl make_pin(const std::string& name, PinDir dir, PinKind kind, const std::string& format, const std::string& doc,
                 PinOptions o) {
    PinDecl p;
    p.name = name;
    p.dir = dir;
    p.kind = kind;
    p.format = format;
    p.optional = o.optional;
    p.mips = o.mips;
    p.scale = o.scale;
    p.same_params = o.same_params;
    p.doc = doc;
    return p;
}
}  // namespace

PassTypeBuilder& PassTypeBuilder::input_texture(const std::string& name, const std::string& format,
                                                const std::string& doc, PinOptions o) {
    info_.pins.push_back(make_pin(name, PinDir::Input, PinKind::Texture, format, doc, o));
    return *this;
}
PassTypeBuilder& PassTypeBuilder::output_texture(const std::string& name, const std::string& format,
                                                 const std::string& doc, PinOptions o) {
    info_.pins.push_back(make_pin(name, PinDir::Output, PinKind::Texture, format, doc, o));
    return *this;
}
PassTypeBuilder& PassTypeBuilder::internal_texture(const std::string& name, const std::string& format,
                                                   const std::string& doc, PinOptions o) {
    o.optional = false;  // always there: the pass's own
    PinDecl p = make_pin(name, PinDir::Output, PinKind::Texture, format, doc, o);
    p.internal = true;
    p.persistent = o.persistent;
    info_.pins.push_back(p);
    return *this;
}
PassTypeBuilder& PassTypeBuilder::internal_buffer(const std::string& name, const std::string& doc, BufferSize size,
                                                  PinOptions o) {
    o.optional = false;  // always there: the pass's own
    output_buffer(name, doc, std::move(size), o);
    info_.pins.back().internal = true;
    info_.pins.back().persistent = o.persistent;
    return *this;
}
PassTypeBuilder& PassTypeBuilder::input_buffer(const std::string& name, const std::string& doc, PinOptions o) {
    info_.pins.push_back(make_pin(name, PinDir::Input, PinKind::Buffer, "", doc, o));
    return *this;
}
PassTypeBuilder& PassTypeBuilder::output_buffer(const std::string& name, const std::string& doc, BufferSize size,
                                                PinOptions o) {
    PinDecl p = make_pin(name, PinDir::Output, PinKind::Buffer, "", doc, o);
    p.bytes = size.bytes;
    p.bytes_per_pixel = size.bytes_per_pixel;
    p.bytes_from_params = std::move(size.from_params);
    info_.pins.push_back(p);
    return *this;
}

// ---- Params ---------------------------------------------------------------------------

const json& Params::at(const std::string& n) const {
    auto it = v_.find(n);
    if (it == v_.end())
        throw std::logic_error("pass '" + pass_ + "' asked for parameter '" + n + "' that its type does not declare");
    return *it;
}
bool Params::b(const std::string& n) const { return at(n).get<bool>(); }
int Params::i(const std::string& n) const { return static_cast<int>(at(n).get<double>()); }
float Params::f(const std::string& n) const { return static_cast<float>(at(n).get<double>()); }
std::string Params::s(const std::string& n) const { return at(n).get<std::string>(); }
int Params::index(const std::string& n) const {
    const std::string v = s(n);
    const ParamDecl* d = type_ ? type_->param(n) : nullptr;
    if (!d || d->type != ParamType::Enum)
        throw std::logic_error("pass '" + pass_ + "' asked for the choice index of '" + n + "', which is not an enum");
    for (size_t i = 0; i < d->choices.size(); ++i)
        if (d->choices[i] == v) return int(i);
    throw std::logic_error("pass '" + pass_ + "': '" + v + "' is not a choice of '" + n + "'");
}
glm::vec3 Params::v3(const std::string& n) const {
    const json& j = at(n);
    return {j.at(0).get<float>(), j.at(1).get<float>(), j.at(2).get<float>()};
}

}  // namespace pathlet
