// Loads pass plugins and registers their pass types. Before a file is opened: it must be named
// pathlet_<name>.so (others in a plugin folder are skipped with a note), lie in a folder that is
// not world-writable and belongs to this user or root, be a regular file of this user or root
// that is not world-writable, and its ELF symbol table (read without loading, plugin_elf.hpp)
// must define pathlet_plugin_v1 and carry this engine's SDK fingerprint. Only then dlopen
// (RTLD_NOW|RTLD_LOCAL), the ABI version and build fingerprint checks, and register_passes.
// Every failure names the file and the reason; nothing here may crash the process.
#pragma once

#include "pass_registry.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace pathlet {

struct PluginError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class PluginHost {
public:
    explicit PluginHost(PassRegistry& registry) : registry_(registry) {}

    // Where plugins are looked for, in order: --plugin-dir values, PATHLET_PLUGIN_PATH
    // (colon-separated), the folder beside libpathlet (build tree and install tree alike).
    static std::vector<std::string> search_path(const std::vector<std::string>& extra_dirs);

    // What a plugin folder holds: files named pathlet_*.so (sorted), and other *.so files that
    // are never opened. Empty when the folder does not exist.
    struct FolderScan {
        std::vector<std::string> plugins, others;
    };
    static FolderScan scan_dir(const std::string& dir);
    // Why plugins may not be loaded from `dir` ("" when they may): world-writable, or owned by
    // another user than this one or root.
    static std::string folder_problem(const std::string& dir);

    // Checks and loads one plugin file; throws PluginError("<file>: <reason>").
    void load_file(const std::string& path);
    // Loads every plugin of the folders; failures are collected in problems(), skipped files in
    // notes(), nothing is thrown.
    void load_dirs(const std::vector<std::string>& dirs);

    struct Loaded {
        std::string file, name;
        std::vector<std::string> types;
    };
    const std::vector<Loaded>& loaded() const { return loaded_; }
    const std::vector<std::string>& problems() const { return problems_; }
    const std::vector<std::string>& notes() const { return notes_; }

private:
    PassRegistry& registry_;
    std::vector<Loaded> loaded_;
    std::vector<std::string> problems_, notes_;
};

// Directory of libpathlet.so itself (to find plugins and shared data relative to it).
std::string engine_library_dir();
// Shared data (shaders/, graphs/): beside the library as ../share/pathlet, else the source tree.
std::string engine_share_dir();

}  // namespace pathlet
