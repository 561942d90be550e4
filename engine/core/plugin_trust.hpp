// Which plugin folders a run may load. Loading a plugin runs its code, and a graph
// or experiment file can name any folder in "plugin_dirs", so:
//   - folders the user names for the run are trusted: --plugin-dir, PATHLET_PLUGIN_PATH, the
//     built-in/installed folder (PluginHost::search_path);
//   - a folder named inside a graph file is loaded only when it is listed in the user's trust
//     file (trust_file_path(): one canonical path per line, `pathlet trust DIR` adds one,
//     `pathlet trust --remove DIR` removes it) or the run allows graph folders
//     (--trust-graph-plugins). Otherwise nothing is loaded: Runtime::load_graph_plugins stops
//     with an error naming the graph, the folder, its plugin files and the command that trusts it.
// Folders are compared by their canonical path (symlinks and ".." resolved), so a link or a
// "trusted/../elsewhere" path is trusted only when the folder it ends at is.
#pragma once

#include <sys/stat.h>

#include <string>
#include <vector>

namespace pathlet {

// Who besides this user and root could change `path` (its stat `st`): "" when nobody, else why,
// naming `what` ("plugin file", "plugin folder", ...): world write access, another owner, and
// with `group_too` group write access. One rule for plugin files, their folders and the trust file.
std::string write_access_problem(const std::string& path, const struct stat& st, const char* what, bool group_too);
// $XDG_CONFIG_HOME/pathlet/trusted-plugin-dirs, else $HOME/.config/pathlet/trusted-plugin-dirs.
std::string trust_file_path();
// The folder's canonical path; "" when it does not exist or is not a folder.
std::string canonical_dir(const std::string& dir);
// The trust file's folders (none when it does not exist). Throws std::runtime_error when it
// cannot be read or others could write it (then none of it can be believed).
std::vector<std::string> read_trusted_dirs();
// Adds a folder (given canonical) / removes one (canonical or as listed); false when there was
// nothing to change. The file is rewritten atomically.
bool add_trusted_dir(const std::string& canonical);
bool remove_trusted_dir(const std::string& dir);
// The command a user runs to trust `dir`, quoted for a shell: pathlet trust '/a b/c'.
std::string trust_command(const std::string& dir);

}  // namespace pathlet
