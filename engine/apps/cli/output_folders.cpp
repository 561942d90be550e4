#include "output_folders.hpp"

#include "image_io.hpp"
#include "util/atomic_file.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace pathlet::cli {
namespace {

std::string canonical(const std::string& path) {
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(path, ec);
    return ec ? path : p.string();
}

std::string owner_of(const std::string& folder) {
    std::ifstream in(fs::path(folder) / kOutputOwnerFile);
    std::string line;
    std::getline(in, line);
    return line;
}

}  // namespace

std::vector<std::string> capture_folders(const CompiledGraph& cg, const std::string& out_dir, glm::ivec2 size) {
    std::vector<std::string> out;
    for (const auto& o : cg.outputs) {
        if (o.capture.empty()) continue;
        std::string file;
        try {
            file = expand_pattern(o.capture,
                                  {{"out", out_dir}, {"graph", cg.name}, {"output", o.resource},
                                   {"size", std::to_string(size.x) + "x" + std::to_string(size.y)}},
                                  0);
        } catch (const std::invalid_argument&) {
            continue;  // the render reports a bad pattern
        }
        const std::string dir = fs::path(file).parent_path().string();
        if (!dir.empty() && std::find(out.begin(), out.end(), dir) == out.end()) out.push_back(dir);
    }
    return out;
}

std::vector<std::string> note_shared_folders(const std::vector<std::string>& folders, const std::string& graph_path) {
    std::vector<std::string> notes;
    const std::string me = canonical(graph_path);
    for (const auto& dir : folders) {
        const std::string owner = owner_of(dir);
        if (owner.empty() || owner == me) continue;
        notes.push_back(dir + "/ holds frames of another graph, " + owner + ", which this render of " + graph_path +
                        " replaces where names meet; give --out DIR or the graph a \"name\" of its own to keep both");
        std::fprintf(stderr, "note: %s\n", notes.back().c_str());
    }
    return notes;
}

void mark_folders(const std::vector<std::string>& folders, const std::string& graph_path) {
    const std::string me = canonical(graph_path);
    for (const auto& dir : folders) {
        std::error_code ec;
        if (!fs::is_directory(dir, ec) || owner_of(dir) == me) continue;
        try {
            write_file_atomic((fs::path(dir) / kOutputOwnerFile).string(), me + "\n");
        } catch (const std::exception& e) {  // the frames are written; only the marker is missing
            std::fprintf(stderr, "warning: %s\n", e.what());
        }
    }
}

}  // namespace pathlet::cli
