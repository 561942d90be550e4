// Graph arguments: a file, or the name of a shipped graph. An argument that is neither is one
// line naming what was given and the closest names, before any data is loaded or folder made.
#include "graph_internal.hpp"
#include "plugin_host.hpp"

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;

namespace pathlet {

using namespace graph_detail;

std::vector<std::string> shipped_graph_names() {
    std::vector<std::string> names;
    std::error_code ec;
    for (fs::directory_iterator it(fs::path(engine_share_dir()) / "graphs", ec), end; !ec && it != end; it.increment(ec))
        if (it->path().extension() == ".json") names.push_back(it->path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

namespace {

// Graph files in `dir` (names as they would be typed: with the folder the argument gave).
std::vector<std::string> json_files_in(const fs::path& dir) {
    std::vector<std::string> out;
    std::error_code ec;
    const fs::path from = dir.empty() ? fs::path(".") : dir;
    for (fs::directory_iterator it(from, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().extension() == ".json") out.push_back((dir / it->path().filename()).string());
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

std::string find_graph_file(const std::string& arg) {
    std::error_code ec;
    if (arg.empty()) throw GraphNotFound("no graph given (a .json file or a shipped graph's name)");
    if (fs::exists(arg, ec)) return arg;  // a folder or an unreadable file: the parser says why
    const fs::path share = fs::path(engine_share_dir()) / "graphs";
    const bool bare = arg.find('/') == std::string::npos;
    if (bare)
        for (const std::string& name : {arg, arg + ".json"})
            if (fs::is_regular_file(share / name, ec)) return (share / name).string();
    // Neither: the closest shipped name, or the closest .json file of the folder it names.
    const std::vector<std::string> shipped = shipped_graph_names();
    std::string hint = bare ? text::closest_match(fs::path(arg).stem().string(), shipped) : "";
    if (hint.empty()) hint = text::closest_match(arg, json_files_in(fs::path(arg).parent_path()));
    std::string msg = "no graph '" + arg + "': no such file, and no shipped graph of that name";
    if (!hint.empty()) msg += " (did you mean '" + hint + "'?)";
    throw GraphNotFound(msg + "; shipped graphs: " + join(shipped));
}

}  // namespace pathlet
