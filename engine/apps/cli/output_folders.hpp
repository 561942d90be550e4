// Which graph a render's output folder belongs to. Two graphs of one name (two files both
// "name": "x", or fig.json in two folders) would write into the same out/x/ and the second would
// replace the first's frames unseen. A record in Pathlet's cache (cache_dir()/output-folders.json,
// never a file among the user's frames) names the graph file that last wrote each folder, and a
// render of another graph into it prints a note first. Best effort: two renders finishing at
// once may keep only one of their records.
#pragma once

#include "graph/graph_model.hpp"

#include <glm/vec2.hpp>

#include <string>
#include <vector>

namespace pathlet::cli {

// The folders the graph's captures write into for these options (frame 0's files' folders).
std::vector<std::string> capture_folders(const CompiledGraph& cg, const std::string& out_dir, glm::ivec2 size);

// Notes (stderr) for each folder the record says another graph file than `graph_path` wrote.
// Returns the notes printed.
std::vector<std::string> note_shared_folders(const std::vector<std::string>& folders, const std::string& graph_path);

// After a render wrote into them: the record names `graph_path` for each existing folder.
void mark_folders(const std::vector<std::string>& folders, const std::string& graph_path);

}  // namespace pathlet::cli
