#include <pathlet/shader_source.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace pathlet {

namespace {

bool is_version_line(const std::string& line) {
    static const std::regex version_re(R"(^\s*#\s*version\b.*$)");
    return std::regex_match(line, version_re);
}

// Where each file's lines are numbered: file k's line n is "#line k*kLinesPerFile+n k". The
// source-string number alone is not enough: Mesa reports source 0 for errors in compound
// expressions (a wrong struct field, a wrong argument type: its parser's default location
// drops the number), so the line itself says the file too (map_log decodes both).
constexpr long kLinesPerFile = 1000000;
std::string line_directive(long line, size_t file) {
    return "#line " + std::to_string(long(file) * kLinesPerFile + line) + " " + std::to_string(file) + "\n";
}

}  // namespace

ShaderSource::ShaderSource(std::vector<std::string> dirs, std::map<HookRole, std::string> hooks)
    : dirs_(std::move(dirs)), hooks_(std::move(hooks)) {}

std::string ShaderSource::find(const std::string& name) const {
    if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos ||
        name.find('\\') != std::string::npos)
        throw ShaderError("shader name '" + name + "' refused: a shader is a file name (no '/', not '..') looked up "
                          "on the shader path");
    for (const auto& d : dirs_) {
        const fs::path p = fs::path(d) / name;
        std::error_code ec;
        if (fs::is_regular_file(p, ec)) return p.string();
    }
    std::string msg = "shader file '" + name + "' not found; searched:";
    for (const auto& d : dirs_) msg += "\n  " + d;
    throw ShaderError(msg);
}

const std::string& ShaderSource::hook(HookRole role) const {
    static const std::string none;
    const auto it = hooks_.find(role);
    return it == hooks_.end() ? none : it->second;
}

std::string ShaderSource::include_target(const std::string& line) {
    static const std::regex include_re(R"(^\s*#\s*include\s+[<"]([^">]+)[">]\s*$)");
    std::smatch m;
    return std::regex_match(line, m, include_re) ? m[1].str() : std::string();
}

std::string ShaderSource::read(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ShaderError(path + ": cannot read");
    std::ostringstream s;
    s << in.rdbuf();
    if (s.str().size() > (1u << 20)) throw ShaderError(path + ": larger than 1 MiB; not a shader");
    return s.str();
}

// An #include is found next to the file that includes it first, then on the search path.
std::string ShaderSource::find_include(const std::string& name, const std::string& from, int line) const {
    std::vector<std::string> search{fs::path(from).parent_path().string()};
    search.insert(search.end(), dirs_.begin(), dirs_.end());
    try {
        return ShaderSource(search).find(name);
    } catch (const ShaderError& e) {
        throw ShaderError(from + ":" + std::to_string(line) + ": #include \"" + name + "\": " + e.what());
    }
}

std::vector<ShaderSource::Text> ShaderSource::with_includes(const std::string& path) const {
    std::vector<Text> out;
    std::set<std::string> seen;
    auto walk = [&](auto& self, const std::string& file, int depth) -> void {
        if (depth > 16) throw ShaderError(file + ": #include nested too deeply (a cycle?)");
        if (!seen.insert(fs::weakly_canonical(file).string()).second) return;
        out.push_back({file, read(file)});
        std::istringstream in(out.back().text);
        std::string line;
        for (int n = 1; std::getline(in, line); ++n)
            if (const std::string name = include_target(line); !name.empty()) self(self, find_include(name, file, n), depth + 1);
    };
    walk(walk, path, 0);
    return out;
}

// Inlines #include "x" recursively under #line numbers of their own. A file's own #version line
// becomes an empty line (compose puts one version line first), so its lines keep their numbers.
std::string ShaderSource::expand(const std::string& path, std::vector<std::string>& numbered, int depth, bool top) const {
    if (depth > 16) throw ShaderError(path + ": #include nested too deeply (a cycle?)");
    const size_t id = numbered.size();
    numbered.push_back(path);
    std::istringstream in(read(path));
    std::ostringstream out;
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        if (const std::string name = include_target(line); !name.empty()) {
            const std::string inc = find_include(name, path, n);
            out << line_directive(1, numbered.size()) << expand(inc, numbered, depth + 1, false)
                << line_directive(n + 1, id);
        } else if (top && is_version_line(line)) {
            out << "\n";
        } else {
            out << line << "\n";
        }
    }
    return out.str();
}

std::string ShaderSource::compose(const std::vector<std::string>& files, const std::vector<std::string>& defines,
                                  std::vector<std::string>& numbered, bool version) const {
    std::ostringstream out;
    if (version) {
        std::string v = "#version 450 core";
        for (auto it = files.rbegin(); it != files.rend(); ++it) {  // the stage's own file decides
            std::istringstream in(read(*it));
            std::string line;
            bool found = false;
            while (!found && std::getline(in, line)) found = is_version_line(line);
            if (found) {
                v = line;
                break;
            }
        }
        out << v << "\n";
        for (const auto& d : defines) out << "#define " << d << "\n";
    }
    for (const auto& f : files) out << line_directive(1, numbered.size()) << expand(f, numbered, 0, true);
    return out.str();
}

std::string ShaderSource::map_log(const std::string& log, const std::vector<std::string>& numbered) {
    static const std::regex mesa(R"(^(\d+):(\d+)\((\d+)\):\s*(.*)$)");
    static const std::regex nv(R"(^(\d+)\((\d+)\)\s*:\s*(.*)$)");
    std::istringstream in(log);
    std::ostringstream out;
    std::string line;
    while (std::getline(in, line)) {
        std::smatch m;
        // "file:line" of source string `idx` and line `at` as the compiler reports them.
        auto place = [&](const std::string& idx, const std::string& at) {
            size_t i = std::stoul(idx);
            long n = std::stol(at);
            if (n >= kLinesPerFile) i = size_t(n / kLinesPerFile), n %= kLinesPerFile;
            return (i < numbered.size() ? numbered[i] : "<source " + std::to_string(i) + ">") + ":" + std::to_string(n);
        };
        if (std::regex_match(line, m, mesa))
            out << place(m[1], m[2]) << ":" << m[3] << ": " << m[4] << "\n";
        else if (std::regex_match(line, m, nv))
            out << place(m[1], m[2]) << ": " << m[3] << "\n";
        else if (!line.empty())
            out << line << "\n";
    }
    return out.str();
}

}  // namespace pathlet
