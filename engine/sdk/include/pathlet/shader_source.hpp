// Where a program's GLSL comes from, said explicitly: the folders searched for shader file
// names, in order, and the hook files the graph resolved for the pass. One finder, one reader
// and one #include rule serve the programs (ShaderProgram), the scan of a hook's @param lines
// and `pathlet validate`; a file is never found by being listed as a folder.
#pragma once

#include <pathlet/hook.hpp>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlet {

struct ShaderError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class ShaderSource {
public:
    ShaderSource() = default;
    ShaderSource(std::vector<std::string> dirs, std::map<HookRole, std::string> hooks = {});  // NOLINT: a path converts

    const std::vector<std::string>& dirs() const { return dirs_; }
    // A shader file name on the search path: the first folder that has it. A name is a file name,
    // never a path ('/' and ".." are refused: a graph names shaders, and "/etc/passwd" or
    // "../../secret" must not reach another file). ShaderError lists the folders searched.
    std::string find(const std::string& name) const;
    // The file the graph resolved for the pass's hook of `role` (absolute), "" when the kit's
    // default serves.
    const std::string& hook(HookRole role) const;
    const std::map<HookRole, std::string>& hooks() const { return hooks_; }

    // A file and every file it #includes, each once, in include order (the file first): what
    // the @param scan reads.
    struct Text {
        std::string path, text;
    };
    std::vector<Text> with_includes(const std::string& path) const;

    // One shader object's source from found files (the last is the stage's own; earlier ones
    // come first, as the kit's definitions before a hook): the version line (the first one of
    // the files, from the last, else the engine's 450 core), `defines`, then each file with its
    // #includes inlined. Every file gets a number for #line, appended to `numbered`, so the
    // compiler's messages can name it (map_log). Without `version`, neither version nor defines
    // (a part appended to another object).
    std::string compose(const std::vector<std::string>& files, const std::vector<std::string>& defines,
                        std::vector<std::string>& numbered, bool version = true) const;
    // Rewrites a compiler log's "0:12(3): error" (Mesa) and "0(12) : error" (NVIDIA) into
    // "file:12: error", with `numbered` from compose.
    static std::string map_log(const std::string& log, const std::vector<std::string>& numbered);

    // The file an `#include "x"` or `#include <x>` line names, or "" for any other line.
    static std::string include_target(const std::string& line);
    // A shader file's text; ShaderError when it cannot be read or is larger than 1 MiB.
    static std::string read(const std::string& path);

private:
    std::string find_include(const std::string& name, const std::string& from, int line) const;
    std::string expand(const std::string& path, std::vector<std::string>& numbered, int depth, bool top) const;

    std::vector<std::string> dirs_;
    std::map<HookRole, std::string> hooks_;
};

}  // namespace pathlet
