// Which graph a render's output folder belongs to. Two graphs of one name (two files both
// "name": "x", or fade.json in two folders) would write into the same out/x/ and the second
// would replace the first's frames unseen: a marker file in each folder names the graph file
// that last wrote there, and a render of another graph into it prints a note first.
#pragma once

#include "graph/graph_model.hpp"

#include <glm/vec2.hpp>

#include <string>
#include <vector>

namespace pathlet::cli {

// The marker's file name inside an output folder.
inline constexpr const char* kOutputOwnerFile = ".pathlet-graph";

// The folders the graph's captures write into for these options (frame 0's files' folders).
std::vector<std::string> capture_folders(const CompiledGraph& cg, const std::string& out_dir, glm::ivec2 size);

// Notes (stderr) for each folder whose marker names another graph file than `graph_path`.
// Returns the notes printed (for tests), empty when none.
std::vector<std::string> note_shared_folders(const std::vector<std::string>& folders, const std::string& graph_path);

// After a render wrote into them: each existing folder's marker names `graph_path`.
void mark_folders(const std::vector<std::string>& folders, const std::string& graph_path);

}  // namespace pathlet::cli
