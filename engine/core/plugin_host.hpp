// Loads pass plugins (dlopen RTLD_NOW|RTLD_LOCAL), checks the ABI version and the build
// fingerprint before calling anything else, and registers their pass types. Every failure
// names the file and the reason; nothing here may crash the process.
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

    // Loads one plugin file; throws PluginError("<file>: <reason>").
    void load_file(const std::string& path);
    // Loads every *.so in the directories; failures are collected, not thrown.
    void load_dirs(const std::vector<std::string>& dirs);

    struct Loaded {
        std::string file, name;
        std::vector<std::string> types;
    };
    const std::vector<Loaded>& loaded() const { return loaded_; }
    const std::vector<std::string>& problems() const { return problems_; }

private:
    PassRegistry& registry_;
    std::vector<Loaded> loaded_;
    std::vector<std::string> problems_;
};

// Directory of libpathlet.so itself (to find plugins and shared data relative to it).
std::string engine_library_dir();
// Shared data (shaders/, graphs/): beside the library as ../share/pathlet, else the source tree.
std::string engine_share_dir();

}  // namespace pathlet
