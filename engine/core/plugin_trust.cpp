#include "plugin_trust.hpp"

#include "util/atomic_file.hpp"
#include "util/text.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace pathlet {

std::string trust_file_path() {
    const char* xdg = std::getenv("XDG_CONFIG_HOME");
    fs::path base;
    if (xdg && *xdg && fs::path(xdg).is_absolute()) base = xdg;  // the spec: relative values are ignored
    else if (const char* home = std::getenv("HOME"); home && *home) base = fs::path(home) / ".config";
    else throw std::runtime_error("neither XDG_CONFIG_HOME nor HOME is set: no place for the plugin trust file");
    return (base / "pathlet" / "trusted-plugin-dirs").string();
}

std::string canonical_dir(const std::string& dir) {
    std::error_code ec;
    const fs::path c = fs::canonical(dir, ec);
    if (ec || !fs::is_directory(c, ec)) return "";
    return c.string();
}

std::string write_access_problem(const std::string& path, const struct stat& st, const char* what, bool group_too) {
    if (st.st_mode & S_IWOTH)
        return path + ": " + what + " is world-writable: anyone on this machine could change it (chmod o-w " + path + ")";
    if (group_too && (st.st_mode & S_IWGRP))
        return path + ": " + what + " is group-writable: others in its group could change it (chmod g-w " + path + ")";
    if (st.st_uid != ::geteuid() && st.st_uid != 0)
        return path + ": " + what + " belongs to another user (uid " + std::to_string(st.st_uid) + "), who could change it";
    return "";
}

std::vector<std::string> read_trusted_dirs() {
    const std::string path = trust_file_path();
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return {};
    if (const std::string why = write_access_problem(path, st, "the plugin trust file", true); !why.empty())
        throw std::runtime_error("the plugin trust file can be changed by other users, so none of it is believed "
                                 "(or remove it and trust the folders again): " + why);
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot read the plugin trust file");
    std::vector<std::string> dirs;
    for (std::string line; std::getline(in, line);) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        if (!line.empty() && line[0] == '/') dirs.push_back(line);  // canonical paths; comments and blanks skipped
    }
    return dirs;
}

namespace {

void write_trusted_dirs(const std::vector<std::string>& dirs) {
    const fs::path path = trust_file_path();
    fs::create_directories(path.parent_path());
    std::string text =
        "# Plugin folders that graph and experiment files may load plugins from (pathlet trust DIR).\n"
        "# One canonical path per line; a folder not listed here is never loaded from a graph's \"plugin_dirs\".\n";
    for (const auto& d : dirs) text += d + "\n";
    write_file_atomic(path.string(), text);
    ::chmod(path.c_str(), 0600);
}

}  // namespace

bool add_trusted_dir(const std::string& canonical) {
    std::vector<std::string> dirs = read_trusted_dirs();
    if (std::find(dirs.begin(), dirs.end(), canonical) != dirs.end()) return false;
    dirs.push_back(canonical);
    write_trusted_dirs(dirs);
    return true;
}

bool remove_trusted_dir(const std::string& dir) {
    std::vector<std::string> dirs = read_trusted_dirs();
    const std::string c = canonical_dir(dir), as_given = fs::absolute(dir).lexically_normal().string();
    const auto gone = std::remove_if(dirs.begin(), dirs.end(),
                                     [&](const std::string& d) { return d == c || d == as_given || d == dir; });
    if (gone == dirs.end()) return false;
    dirs.erase(gone, dirs.end());
    write_trusted_dirs(dirs);
    return true;
}

std::string trust_command(const std::string& dir) { return "pathlet trust " + text::shell_quote(dir); }

}  // namespace pathlet
