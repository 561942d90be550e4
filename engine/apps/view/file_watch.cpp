#include "view/file_watch.hpp"

#include <set>

namespace fs = std::filesystem;

namespace pathlet::view {

FileWatch::State FileWatch::look(const std::string& f) {
    State s;
    std::error_code ec;
    s.exists = fs::is_regular_file(f, ec);
    if (s.exists) {
        s.mtime = fs::last_write_time(f, ec);
        s.bytes = fs::file_size(f, ec);
    }
    return s;
}

void FileWatch::watch(const std::vector<std::string>& files) {
    state_.clear();
    for (const auto& f : files) state_[f] = look(f);
}

std::vector<std::string> FileWatch::changed() {
    std::vector<std::string> out;
    for (auto& [f, s] : state_) {
        State now = look(f);
        if (now != s) out.push_back(f), s = now;
    }
    return out;
}

std::vector<std::string> graph_and_shader_files(const std::string& graph, const std::vector<std::string>& shader_dirs,
                                                const std::vector<std::string>& hook_files) {
    std::set<std::string> files{graph};
    files.insert(hook_files.begin(), hook_files.end());  // a hook file the user named by path may lie anywhere
    for (const auto& d : shader_dirs) {
        std::error_code ec;
        for (fs::directory_iterator it(d, ec), end; !ec && it != end; it.increment(ec)) {
            const std::string ext = it->path().extension().string();
            if (ext == ".glsl" || ext == ".vert" || ext == ".geom" || ext == ".frag" || ext == ".comp")
                files.insert(it->path().string());
        }
    }
    return {files.begin(), files.end()};
}

}  // namespace pathlet::view
