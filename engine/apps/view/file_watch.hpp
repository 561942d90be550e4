// Which of a set of files changed on disk since the last look (modification time and size):
// `pathlet view` polls its graph and shader files with it for hot reload. No GL, no threads.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace pathlet::view {

class FileWatch {
public:
    // Replaces the watched set and remembers each file's current state.
    void watch(const std::vector<std::string>& files);
    // Files whose state differs from the last call (or from watch()); a file that appears,
    // disappears or is rewritten counts. Remembers the new states.
    std::vector<std::string> changed();
    size_t size() const { return state_.size(); }

private:
    struct State {
        bool exists = false;
        std::filesystem::file_time_type mtime{};
        std::uintmax_t bytes = 0;
        bool operator!=(const State& o) const { return exists != o.exists || mtime != o.mtime || bytes != o.bytes; }
    };
    static State look(const std::string& f);
    std::map<std::string, State> state_;
};

// The files a graph depends on for hot reload: the graph itself, every .glsl/.vert/.geom/.frag
// in the given shader folders, and the hook files (a hook the user named by path may lie anywhere).
std::vector<std::string> graph_and_shader_files(const std::string& graph, const std::vector<std::string>& shader_dirs,
                                                const std::vector<std::string>& hook_files = {});

}  // namespace pathlet::view
