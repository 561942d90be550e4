#include "hook_params.hpp"

#include "graph_internal.hpp"
#include "plugin_host.hpp"

#include <pathlet/shader.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
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

std::vector<std::string> hook_search_path(const PassTypeInfo& type, const std::vector<std::string>& graph_dirs) {
    std::vector<std::string> dirs = graph_dirs;
    for (auto& d : shader_search_path(type, {}))
        if (std::find(dirs.begin(), dirs.end(), d) == dirs.end()) dirs.push_back(std::move(d));
    return dirs;
}

bool is_chosen_file(const std::string& name, const std::vector<std::string>& dirs) {
    return fs::path(name).is_absolute() && std::find(dirs.begin(), dirs.end(), name) != dirs.end();
}

std::string check_hook_name(const std::string& name, const std::vector<std::string>& graph_dirs) {
    if (name.empty()) return "";
    if (!is_chosen_file(name, graph_dirs) &&
        (name.find('/') != std::string::npos || name.find('\\') != std::string::npos || name.find("..") != std::string::npos ||
         name[0] == '.'))
        return "a hook a graph names is a file name on the shader path or next to the graph, without folders or '..' "
               "(a path is yours to give: --set PASS.color_hook=PATH on the command line, Graph.set in Python)";
    const std::string ext = fs::path(name).extension().string();
    if (ext != ".frag" && ext != ".geom" && ext != ".glsl") return "a hook file ends in .frag, .geom or .glsl";
    return "";
}

namespace {

struct Source {
    std::string file;  // as found
    std::string text;
};

std::string find_file(const std::string& name, const std::vector<std::string>& dirs) {
    if (is_chosen_file(name, dirs)) {  // a path the user gave (check_hook_name refused any other)
        std::error_code ec;
        if (fs::is_regular_file(name, ec)) return name;
        throw HookError("hook file '" + name + "' not found");
    }
    for (const auto& d : dirs) {
        const fs::path p = fs::path(d) / name;
        std::error_code ec;
        if (fs::is_regular_file(p, ec)) return p.string();
    }
    std::string msg = "hook file '" + name + "' not found; searched:";
    for (const auto& d : dirs) msg += "\n  " + d;
    throw HookError(msg);
}

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw HookError(path + ": cannot read");
    std::ostringstream s;
    s << in.rdbuf();
    if (s.str().size() > (1u << 20)) throw HookError(path + ": larger than 1 MiB; not a hook");
    return s.str();
}

// The hook file and every file it includes (each once), in include order.
void collect(const std::string& path, const std::vector<std::string>& dirs, std::vector<Source>& out,
             std::set<std::string>& seen, int depth) {
    if (depth > 16) throw HookError(path + ": #include nested too deeply (a cycle?)");
    if (!seen.insert(fs::weakly_canonical(path).string()).second) return;
    out.push_back({path, read_text(path)});
    std::istringstream in(out.back().text);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        const std::string name = include_target(line);  // the includes the compiler inlines
        if (name.empty()) continue;
        std::vector<std::string> search{fs::path(path).parent_path().string()};
        search.insert(search.end(), dirs.begin(), dirs.end());
        std::string inc;
        try {
            inc = find_shader_file(name, search);  // and found as it finds them
        } catch (const ShaderError& e) {
            throw HookError(path + ":" + std::to_string(n) + ": #include \"" + name + "\": " + e.what());
        }
        collect(inc, dirs, out, seen, depth + 1);
    }
}

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

const char* hook_function(const std::string& role) {
    return role == "width" ? "float line_width_hook(LinePoint p)" : "vec4 line_color_hook(vec4 rgba, LinePoint p)";
}

// The hook's function must be defined (not only declared) in the file or what it includes.
void check_function(const std::string& name, const std::string& role, const std::vector<Source>& sources) {
    const std::string fn = role == "width" ? "line_width_hook" : "line_color_hook";
    const std::regex def_re("\\b" + fn + R"(\s*\([^;{)]*\)\s*\{)");
    for (const auto& s : sources)
        if (std::regex_search(s.text, def_re)) return;
    // Name what it defines instead, with its line: a typo is the usual cause.
    static const std::regex any_def(R"(\b(\w+)\s*\([^;{)]*\)\s*\{)");
    std::vector<std::string> defined;
    std::map<std::string, int> line_of;
    const Source& own = sources.front();
    for (auto it = std::sregex_iterator(own.text.begin(), own.text.end(), any_def); it != std::sregex_iterator(); ++it) {
        const std::string f = (*it)[1].str();
        if (f == "if" || f == "for" || f == "while" || f == "switch" || f == "main") continue;
        defined.push_back(f);
        line_of.emplace(f, 1 + int(std::count(own.text.begin(), own.text.begin() + it->position(), '\n')));
    }
    const std::string near = text::closest_match(fn, defined);
    throw HookError(own.file + ":" + std::to_string(near.empty() ? 1 : line_of[near]) + ": a " +
                    (role == "width" ? "width" : "colour") + " hook defines " + hook_function(role) +
                    (near.empty() ? "; this file defines no such function" : "; this file defines '" + near + "' instead"));
}

}  // namespace

std::vector<ParamDecl> hook_params(const std::string& name, const std::string& role,
                                   const std::vector<std::string>& dirs) {
    std::vector<Source> sources;
    std::set<std::string> seen;
    collect(find_file(name, dirs), dirs, sources, seen, 0);
    check_function(name, role, sources);
    static const std::regex decl_re(R"(^\s*uniform\s+(float|int|bool|vec3)\s+u_(\w+)\s*;\s*//\s*@param\b(.*)$)");
    std::vector<ParamDecl> out;
    for (const auto& s : sources) {
        std::istringstream in(s.text);
        std::string line;
        for (int n = 1; std::getline(in, line); ++n) {
            // Code lines whose comment starts with @param (prose about @param in comments is no declaration).
            static const std::regex marker(R"(^\s*[^/\s*].*//\s*@param\b)");
            if (line.find("@param") == std::string::npos || !std::regex_search(line, marker)) continue;
            const std::string where = fs::path(s.file).filename().string() + ":" + std::to_string(n);
            std::smatch m;
            if (!std::regex_match(line, m, decl_re))
                throw HookError(s.file + ":" + std::to_string(n) +
                                ": @param belongs after 'uniform float|int|bool|vec3 u_<name>;' on the same line");
            ParamDecl d = ParamLine(m[3].str(), s.file + ":" + std::to_string(n)).parse(m[1].str(), m[2].str());
            d.origin = where;
            out.push_back(std::move(d));
        }
    }
    return out;
}

std::string find_hook_file(const std::string& name, const PassTypeInfo& type, const std::vector<std::string>& graph_dirs) {
    return find_file(name, hook_search_path(type, graph_dirs));
}

std::shared_ptr<const PassTypeInfo> instance_type(const PassTypeInfo& type, const json& params,
                                                  const std::vector<std::string>& graph_dirs) {
    std::vector<ParamDecl> extra;
    std::vector<std::string> dirs;
    for (const ParamDecl& hook : type.params) {
        if (hook.hook.empty()) continue;
        const auto it = params.find(hook.name);
        const std::string file = it != params.end() && it->is_string() ? it->get<std::string>() : hook.def.get<std::string>();
        if (file.empty()) continue;  // the kit's default hook: no parameters
        if (std::string err = check_hook_name(file, graph_dirs); !err.empty())
            throw HookError(hook.name + " '" + file + "': " + err);
        if (dirs.empty()) dirs = hook_search_path(type, graph_dirs);
        for (ParamDecl& d : hook_params(file, hook.hook, dirs)) {
            if (const ParamDecl* clash = type.param(d.name))
                throw HookError(d.origin + ": parameter '" + d.name + "' is already one of pass type '" + type.type +
                                "'s (" + clash->doc.substr(0, 40) + "...); name the uniform differently");
            const auto same = std::find_if(extra.begin(), extra.end(), [&](const ParamDecl& e) { return e.name == d.name; });
            if (same == extra.end()) extra.push_back(std::move(d));
            else if (same->origin != d.origin)  // both hooks include one file: the same declaration
                throw HookError(d.origin + ": parameter '" + d.name + "' is declared again (first at " + same->origin +
                                ")");
        }
    }
    if (extra.empty()) return std::shared_ptr<const PassTypeInfo>(&type, [](const PassTypeInfo*) {});
    auto t = std::make_shared<PassTypeInfo>(type);
    for (auto& d : extra) t->params.push_back(std::move(d));
    return t;
}

}  // namespace pathlet
