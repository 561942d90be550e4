#include "shader_interlock.hpp"

#include <filesystem>
#include <cctype>
#include <regex>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace pathlet {

namespace {

// The source without comments (for what it declares: a commented-out layout declares nothing).
std::string without_comments(const std::string& src) {
    static const std::regex comments(R"(/\*[\s\S]*?\*/|//[^\n]*)");
    return std::regex_replace(src, comments, " ");
}

bool declares_interlock(const std::string& src) {
    static const std::regex decl(R"(\blayout\s*\(([^)]*)\)\s*in\s*;)");
    static const std::regex qualifier(R"(\b(pixel|sample)_interlock_(un)?ordered\b)");
    const std::string code = without_comments(src);
    for (auto it = std::sregex_iterator(code.begin(), code.end(), decl); it != std::sregex_iterator(); ++it)
        if (std::regex_search((*it)[1].str(), qualifier)) return true;
    return false;
}

std::string squeezed(const std::string& line) {
    std::string out;
    for (char c : line)
        if (!std::isspace(static_cast<unsigned char>(c))) out += c;
    return out;
}

// `more` with its #extension lines taken out (into `extensions`) and the uniform declarations
// `main` already makes the same way blanked: each line stays, so #line numbers hold.
std::string fit_into(const std::string& main, const std::string& more, std::string& extensions) {
    static const std::regex extension(R"(^\s*#\s*extension\b.*$)");
    static const std::regex uniform(R"(^\s*uniform\s+[^;{]*;\s*(//.*)?$)");
    std::set<std::string> declared;
    {
        std::istringstream in(main);
        for (std::string line; std::getline(in, line);)
            if (std::regex_match(line, uniform)) declared.insert(squeezed(line.substr(0, line.find("//"))));
    }
    std::istringstream in(more);
    std::ostringstream out;
    for (std::string line; std::getline(in, line);) {
        if (std::regex_match(line, extension)) {
            extensions += line + "\n";
            out << "\n";
        } else if (std::regex_match(line, uniform) && declared.count(squeezed(line.substr(0, line.find("//"))))) {
            out << "\n";
        } else {
            out << line << "\n";
        }
    }
    return out.str();
}

}  // namespace

void merge_interlocked_fragments(std::vector<ShaderUnit>& units, const ShaderSource& source) {
    size_t m = 0;
    while (m < units.size() && !(units[m].stage == GL_FRAGMENT_SHADER && declares_interlock(units[m].src))) ++m;
    if (m == units.size()) return;
    ShaderUnit& main = units[m];
    std::string extensions, appended;
    for (size_t k = 0; k < units.size(); ++k) {
        if (k == m || units[k].stage != GL_FRAGMENT_SHADER) continue;
        const std::string more = source.compose(units[k].files, {}, main.numbered, /*version=*/false);
        main.src += fit_into(main.src, more, extensions);
        main.path.append("+").append(fs::path(units[k].path).filename().string());
        appended += (appended.empty() ? "" : ", ") + units[k].path;
    }
    if (appended.empty()) return;
    const size_t after_version = main.src.find('\n') + 1;
    main.src.insert(after_version, extensions);
    main.merge_note = "\n(the fragment stage uses the fragment shader interlock, so it is compiled as one object: " +
                      fs::path(main.files.back()).filename().string() + " with " + appended +
                      " appended; a declaration both make must be made once, or renamed in the appended file)";
    std::vector<ShaderUnit> kept;
    for (size_t k = 0; k < units.size(); ++k)
        if (k == m || units[k].stage != GL_FRAGMENT_SHADER) kept.push_back(std::move(units[k]));
    units = std::move(kept);
}

}  // namespace pathlet
