#include "hook_params.hpp"

#include "graph_internal.hpp"
#include "plugin_host.hpp"

#include <pathlet/shader_source.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;

namespace pathlet {

using graph_detail::did_you_mean;

std::vector<std::string> shader_search_path(const PassTypeInfo& type, const std::vector<std::string>& graph_dirs) {
    std::vector<std::string> dirs;
    if (const char* env = std::getenv("PATHLET_SHADER_PATH")) {
        std::stringstream s(env);
        std::string d;
        while (std::getline(s, d, ':'))
            if (!d.empty()) dirs.push_back(d);
    }
    if (!type.plugin_file.empty()) {
        fs::path so(type.plugin_file);
        dirs.push_back((so.parent_path() / so.stem()).string());  // <plugin dir>/<plugin>/ (installed shaders)
    }
    dirs.push_back((fs::path(engine_share_dir()) / "shaders").string());
    for (const auto& d : graph_dirs)
        if (std::find(dirs.begin(), dirs.end(), d) == dirs.end()) dirs.push_back(d);
    return dirs;
}

ShaderSource pass_shaders(const PassTypeInfo& type, const std::vector<std::string>& graph_dirs,
                          const std::vector<HookBinding>& hooks) {
    std::map<HookRole, std::string> files;
    for (const auto& h : hooks) files[h.role] = h.file;
    return ShaderSource(shader_search_path(type, graph_dirs), std::move(files));
}

std::string check_hook_name(const std::string& name, const std::set<std::string>& user_files) {
    if (name.empty()) return "";
    if (!(fs::path(name).is_absolute() && user_files.count(name)) &&
        (name.find('/') != std::string::npos || name.find('\\') != std::string::npos || name.find("..") != std::string::npos ||
         name[0] == '.'))
        return "a hook a graph names is a file name on the shader path or next to the graph, without folders or '..' "
               "(a path is yours to give: --set PASS.color_hook=PATH on the command line, Graph.set in Python)";
    const std::string ext = fs::path(name).extension().string();
    if (ext != ".frag" && ext != ".geom" && ext != ".glsl") return "a hook file ends in .frag, .geom or .glsl";
    return "";
}

namespace {

// The text after "@param": tokens of the little grammar in hook_params.hpp.
class ParamLine {
public:
    ParamLine(std::string text, std::string where) : s_(std::move(text)), where_(std::move(where)) {}

    ParamDecl parse(const std::string& glsl_type, const std::string& name) {
        ParamDecl d;
        d.name = name;
        skip();
        const bool color = word("color");
        json def;
        if (glsl_type == "float" || glsl_type == "int") {
            def = scalar(token());  // a number, or (int) an enum's choice
            if (!def.is_number() && glsl_type == "float") fail("expected a number as the default");
            d.type = glsl_type == "float" ? ParamType::Float : ParamType::Int;
        } else if (glsl_type == "bool") {
            d.type = ParamType::Bool;
            if (word("true")) def = true;
            else if (word("false")) def = false;
            else fail("a bool parameter's default is true or false");
        } else {  // vec3
            d.type = color ? ParamType::Color : ParamType::Vec3;
            skip();
            if (color && peek() == '#') def = token();
            else def = triple();
        }
        if (color && glsl_type != "vec3") fail("'color' applies to vec3 uniforms");
        skip();
        if (peek() == '[') {
            if (d.type != ParamType::Float && d.type != ParamType::Int) fail("a range [min, max] applies to float and int");
            json r = list('[', ']');
            if (r.size() != 2 || !r[0].is_number() || !r[1].is_number() || r[0].get<double>() > r[1].get<double>())
                fail("a range is [min, max] with min <= max");
            d.min = r[0].get<double>();
            d.max = r[1].get<double>();
        } else if (peek() == '{') {
            if (glsl_type != "int") fail("choices {a, b, ...} apply to int uniforms (the index of the choice)");
            d.type = ParamType::Enum;
            for (const auto& c : list('{', '}')) d.choices.push_back(c.get<std::string>());
            if (d.choices.empty()) fail("an enum needs at least one choice");
        }
        skip();
        if (word("px")) {
            if (d.type != ParamType::Float && d.type != ParamType::Int) fail("'px' applies to float and int");
            d.pixels = true;
        }
        skip();
        if (peek() != '"') fail("a parameter needs a doc string in double quotes at the end");
        const size_t close = s_.rfind('"');
        if (close <= i_) fail("the doc string has no closing quote");
        d.doc = s_.substr(i_ + 1, close - i_ - 1);
        if (d.type == ParamType::Int && !def.is_number()) fail("expected a number as the default (or {choices} after a choice)");
        if (d.type == ParamType::Enum) {
            if (!def.is_string()) fail("an enum's default is one of its choices");
        } else if (d.type == ParamType::Int && def.is_number() && def.get<double>() != std::floor(def.get<double>())) {
            fail("an int parameter's default must be whole");
        }
        if (std::string err = d.coerce(def, d.def); !err.empty()) fail("default " + err);
        return d;
    }

private:
    [[noreturn]] void fail(const std::string& msg) const { throw HookError(where_ + ": @param: " + msg); }
    void skip() {
        while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
    }
    char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
    bool word(const char* w) {
        skip();
        const size_t n = std::strlen(w);
        if (s_.compare(i_, n, w) == 0 && (i_ + n == s_.size() || !std::isalnum(static_cast<unsigned char>(s_[i_ + n])))) {
            i_ += n;
            return true;
        }
        return false;
    }
    std::string token() {  // up to white space, a comma or a bracket
        skip();
        size_t b = i_;
        while (i_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[i_])) && s_[i_] != ',' &&
               std::string("[]{}\"").find(s_[i_]) == std::string::npos)
            ++i_;
        if (b == i_) fail("expected a value");
        return s_.substr(b, i_ - b);
    }
    json scalar(const std::string& t) const {
        char* end = nullptr;
        const double v = std::strtod(t.c_str(), &end);
        if (end && *end == '\0' && !t.empty()) return v;
        return t;  // an enum choice
    }
    json triple() {
        skip();
        if (peek() != '[') fail("a vec3 default is [x, y, z]");
        json v = list('[', ']');
        if (v.size() != 3) fail("a vec3 default has three numbers");
        return v;
    }
    json list(char open, char close) {
        skip();
        if (peek() != open) fail(std::string("expected '") + open + "'");
        ++i_;
        json out = json::array();
        for (;;) {
            skip();
            if (peek() == close) {
                ++i_;
                return out;
            }
            out.push_back(scalar(token()));
            skip();
            if (peek() == ',') ++i_;
            else if (peek() != close) fail(std::string("expected ',' or '") + close + "'");
        }
    }

    std::string s_, where_;
    size_t i_ = 0;
};

// The role's function must be defined (not only declared) in the file or what it includes.
void check_function(HookRole role, const std::vector<ShaderSource::Text>& sources) {
    const HookRoleInfo& r = hook_role(role);
    const std::regex def_re(std::string("\\b") + r.function + R"(\s*\([^;{)]*\)\s*\{)");
    for (const auto& s : sources)
        if (std::regex_search(s.text, def_re)) return;
    // Name what it defines instead, with its line: a typo is the usual cause.
    static const std::regex any_def(R"(\b(\w+)\s*\([^;{)]*\)\s*\{)");
    std::vector<std::string> defined;
    std::map<std::string, int> line_of;
    const auto& own = sources.front();
    for (auto it = std::sregex_iterator(own.text.begin(), own.text.end(), any_def); it != std::sregex_iterator(); ++it) {
        const std::string f = (*it)[1].str();
        if (f == "if" || f == "for" || f == "while" || f == "switch" || f == "main") continue;
        defined.push_back(f);
        line_of.emplace(f, 1 + int(std::count(own.text.begin(), own.text.begin() + it->position(), '\n')));
    }
    const std::string near = text::closest_match(r.function, defined);
    throw HookError(own.path + ":" + std::to_string(near.empty() ? 1 : line_of[near]) + ": a " + r.noun +
                    " hook defines " + r.signature +
                    (near.empty() ? "; this file defines no such function" : "; this file defines '" + near + "' instead"));
}

// The parameters a hook file and what it includes declare with @param, in file order.
std::vector<ParamDecl> scan_params(const std::vector<ShaderSource::Text>& sources) {
    static const std::regex decl_re(R"(^\s*uniform\s+(float|int|bool|vec3)\s+u_(\w+)\s*;\s*//\s*@param\b(.*)$)");
    // Code lines whose comment starts with @param (prose about @param in comments is no declaration).
    static const std::regex marker(R"(^\s*[^/\s*].*//\s*@param\b)");
    std::vector<ParamDecl> out;
    for (const auto& s : sources) {
        std::istringstream in(s.text);
        std::string line;
        for (int n = 1; std::getline(in, line); ++n) {
            if (line.find("@param") == std::string::npos || !std::regex_search(line, marker)) continue;
            const std::string where = s.path + ":" + std::to_string(n);
            std::smatch m;
            if (!std::regex_match(line, m, decl_re))
                throw HookError(where + ": @param belongs after 'uniform float|int|bool|vec3 u_<name>;' on the same line");
            ParamDecl d = ParamLine(m[3].str(), where).parse(m[1].str(), m[2].str());
            d.origin = fs::path(s.path).filename().string() + ":" + std::to_string(n);
            out.push_back(std::move(d));
        }
    }
    return out;
}

}  // namespace

HookBinding bind_hook(const PassTypeInfo& type, HookRole role, const std::string& name,
                      const std::vector<std::string>& graph_dirs, const std::set<std::string>& user_files) {
    const HookRoleInfo& r = hook_role(role);
    if (std::string err = check_hook_name(name, user_files); !err.empty())
        throw HookError(std::string(r.param) + " '" + name + "': " + err);
    HookBinding b{role, r.param, name, "", {}};
    std::error_code ec;
    if (fs::path(name).is_absolute()) {  // a file the user named (check_hook_name refused any other path)
        if (!fs::is_regular_file(name, ec)) throw HookError("hook file '" + name + "' not found");
        b.file = name;
    } else {
        // Next to the graph first, then on the shader path.
        std::vector<std::string> dirs = graph_dirs;
        for (auto& d : shader_search_path(type, {}))
            if (std::find(dirs.begin(), dirs.end(), d) == dirs.end()) dirs.push_back(std::move(d));
        try {
            b.file = ShaderSource(dirs).find(name);
        } catch (const ShaderError&) {
            std::string msg = "hook file '" + name + "' not found; searched:";
            for (const auto& d : dirs) msg += "\n  " + d;
            throw HookError(msg);
        }
    }
    b.file = fs::absolute(b.file).lexically_normal().string();
    try {
        const auto sources = ShaderSource(shader_search_path(type, graph_dirs)).with_includes(b.file);
        check_function(role, sources);
        b.params = scan_params(sources);
    } catch (const ShaderError& e) {
        throw HookError(e.what());
    }
    return b;
}

std::shared_ptr<const PassTypeInfo> instance_type(const PassTypeInfo& type, const std::vector<HookBinding>& hooks) {
    std::vector<ParamDecl> extra;
    for (const HookBinding& h : hooks) {
        for (const ParamDecl& d : h.params) {
            if (const ParamDecl* clash = type.param(d.name))
                throw HookError(d.origin + ": parameter '" + d.name + "' is already one of pass type '" + type.type +
                                "'s (" + clash->doc.substr(0, 40) + "...); name the uniform differently");
            const auto same = std::find_if(extra.begin(), extra.end(), [&](const ParamDecl& e) { return e.name == d.name; });
            if (same == extra.end()) extra.push_back(d);
            else if (same->origin != d.origin)  // both hooks include one file: the same declaration
                throw HookError(d.origin + ": parameter '" + d.name + "' is declared again (first at " + same->origin + ")");
        }
    }
    if (extra.empty()) return std::shared_ptr<const PassTypeInfo>(&type, [](const PassTypeInfo*) {});
    auto t = std::make_shared<PassTypeInfo>(type);
    for (auto& d : extra) t->params.push_back(std::move(d));
    return t;
}

std::shared_ptr<const PassTypeInfo> instance_type_with(const PassTypeInfo& type,
                                                       const std::map<HookRole, std::string>& names,
                                                       const std::set<std::string>& user_files) {
    std::vector<HookBinding> hooks;
    for (const ParamDecl& d : type.params) {
        if (!d.hook) continue;
        const auto given = names.find(*d.hook);
        const std::string name = given != names.end() ? given->second : d.def.get<std::string>();
        if (!name.empty()) hooks.push_back(bind_hook(type, *d.hook, name, {}, user_files));
    }
    return instance_type(type, hooks);
}

}  // namespace pathlet
