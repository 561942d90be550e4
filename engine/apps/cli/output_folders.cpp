#include "output_folders.hpp"

#include "image_io.hpp"
#include "util/atomic_file.hpp"
#include "util/cache_dir.hpp"
#include "util/text.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace fs = std::filesystem;

namespace pathlet::cli {
namespace {

constexpr size_t kMaxRecords = 2000;  // the oldest go first

std::string canonical(const std::string& path) {
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(path, ec);
    return ec ? path : p.string();
}

std::string record_file() { return (fs::path(cache_dir()) / "output-folders.json").string(); }

// [[folder, graph], ...], oldest first; empty when there is none or it cannot be read.
nlohmann::json read_records() {
    std::error_code ec;
    if (!fs::is_regular_file(record_file(), ec)) return nlohmann::json::array();
    try {
        nlohmann::json j = text::read_json_file(record_file(), "output folder record");
        if (j.is_array()) return j;
    } catch (const std::exception&) {
    }
    return nlohmann::json::array();
}

std::string owner_of(const nlohmann::json& records, const std::string& folder) {
    for (auto it = records.rbegin(); it != records.rend(); ++it)
        if (it->is_array() && it->size() == 2 && (*it)[0] == folder && (*it)[1].is_string()) return (*it)[1];
    return "";
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
    const nlohmann::json records = read_records();
    const std::string me = canonical(graph_path);
    for (const auto& dir : folders) {
        const std::string owner = owner_of(records, canonical(dir));
        std::error_code ec;
        if (owner.empty() || owner == me || !fs::is_directory(dir, ec)) continue;
        notes.push_back(dir + "/ holds frames of another graph, " + owner + ", which this render of " + graph_path +
                        " replaces where names meet; give --out DIR or the graph a \"name\" of its own to keep both");
        std::fprintf(stderr, "note: %s\n", notes.back().c_str());
    }
    return notes;
}

void mark_folders(const std::vector<std::string>& folders, const std::string& graph_path) {
    nlohmann::json records = read_records();
    const std::string me = canonical(graph_path);
    bool changed = false;
    for (const auto& dir : folders) {
        std::error_code ec;
        const std::string folder = canonical(dir);
        if (!fs::is_directory(dir, ec) || owner_of(records, folder) == me) continue;
        records.push_back({folder, me});
        changed = true;
    }
    if (!changed) return;
    if (records.size() > kMaxRecords) records.erase(records.begin(), records.begin() + long(records.size() - kMaxRecords));
    try {
        fs::create_directories(cache_dir());
        write_file_atomic(record_file(), records.dump());
    } catch (const std::exception& e) {  // the frames are written; only the record is missing
        std::fprintf(stderr, "warning: %s\n", e.what());
    }
}

}  // namespace pathlet::cli
