// pathlet trust [DIR | --remove DIR]: the plugin folders graph and experiment files may load.
#include "commands.hpp"
#include "common_options.hpp"
#include "plugin_host.hpp"
#include "plugin_trust.hpp"

#include <cstdio>
#include <filesystem>

namespace pathlet::cli {
namespace {

int list() {
    const std::vector<std::string> dirs = read_trusted_dirs();
    std::printf("trusted plugin folders (%s):\n", trust_file_path().c_str());
    if (dirs.empty()) std::printf("  (none)\n");
    for (const auto& d : dirs) std::printf("  %s%s\n", d.c_str(), canonical_dir(d) == d ? "" : "   (gone)");
    return 0;
}

int trust(const std::string& dir) {
    const std::string c = canonical_dir(dir);
    if (c.empty()) throw std::runtime_error(dir + ": no such folder");
    // A folder others can write to would be trusted for whatever they put in it.
    if (std::string why = PluginHost::folder_problem(c); !why.empty()) throw std::runtime_error(why + "; not trusted");
    const auto scan = PluginHost::scan_dir(c);
    const bool added = add_trusted_dir(c);
    std::printf("%s %s (%zu plugin file%s) in %s\n", added ? "trusted" : "already trusted:", c.c_str(),
                scan.plugins.size(), scan.plugins.size() == 1 ? "" : "s", trust_file_path().c_str());
    return 0;
}

int untrust(const std::string& dir) {
    if (!remove_trusted_dir(dir)) {
        std::fprintf(stderr, "pathlet trust: %s is not in %s (see 'pathlet trust')\n", dir.c_str(), trust_file_path().c_str());
        return 1;
    }
    std::printf("no longer trusted: %s\n", dir.c_str());
    return 0;
}

int run(const std::vector<std::string>& argv) {
    Args a("trust",
           "Plugin folders that graph and experiment files may load plugins from. Loading a plugin runs its\n"
           "code, and a graph file can name any folder in \"plugin_dirs\", so such a folder is loaded only\n"
           "when it is trusted: listed in the trust file (one canonical path per line, symlinks and '..'\n"
           "resolved; $XDG_CONFIG_HOME/pathlet/trusted-plugin-dirs, else ~/.config/pathlet/...), or allowed\n"
           "for one run with --trust-graph-plugins. Otherwise the command stops before loading anything and\n"
           "names the folder. Folders given with --plugin-dir or PATHLET_PLUGIN_PATH and the built-in one are\n"
           "trusted because you chose them. A folder anyone can write to, or another user's, is never\n"
           "trusted. Without arguments: the list.");
    std::string dir, remove;
    a.positional("DIR", dir, "folder to trust", false)
        .option("remove", remove, "DIR", "stop trusting DIR")
        .example("pathlet trust plugins/example_fade/build", "graphs naming this folder may load its plugins")
        .example("pathlet trust --remove plugins/example_fade/build", "and no longer")
        .example("pathlet trust", "the trusted folders and the file that lists them");
    if (!a.parse(argv)) return 0;
    if (!dir.empty() && !remove.empty()) throw UsageError("give DIR or --remove DIR, not both");
    if (!remove.empty()) return untrust(remove);
    return dir.empty() ? list() : trust(dir);
}

PATHLET_COMMAND("trust", "trust a plugin folder that graph files name (or --remove it; no argument: the list)", run);

}  // namespace
}  // namespace pathlet::cli
