// What data to load and loading it: the data options of a command (cli's SceneOptions), an
// experiment's data set (bench) and the Python module all name their data this way.
#pragma once

#include "io/pathline_io.hpp"

#include <pathlet/scene.hpp>

#include <string>
#include <vector>

namespace pathlet {

struct SceneSource {
    // Pathline files, folders (their data files, sorted by name) or glob patterns; empty = the
    // built-in phantom. Several files are joined, each a bundle named after its file's stem.
    std::vector<std::string> data;
    std::string mesh;             // wall mesh file (optional)
    std::string phantom = "study";
    io::LoadOptions load;         // arrays, time step, units, streamlines (units apply to the phantom too)
};

// What the user named as data does not fit together: a folder without data files, a glob that
// matches nothing, two files of one stem (one bundle name), files of mixed kinds. The commands
// exit 2 for it, as for a usage error; the message names the files.
struct DataChoiceError : DataError {
    using DataError::DataError;
};

// The files `given` names, in order: a folder gives its data files sorted by name, a pattern
// with * ? or [ that is not a file gives its matches sorted (what a shell would have expanded).
// DataChoiceError for an empty folder, a pattern matching nothing, two files of one stem or a
// missing file that looks like a graph (a graph name after --data's files).
std::vector<std::string> data_files(const std::vector<std::string>& given);

// The extensions a folder's data files have (pathlines and tracts).
const std::vector<std::string>& data_file_extensions();

// Loads what the source says; unless quiet, prints a one-line summary. Repair warnings go to
// stderr either way (a file that needed repairs should say so). A data set with no line left to
// draw after repair is a DataError naming the file and what the repair dropped. Several files
// are joined in name order (bundle k is the k-th name, whatever the arguments' order).
Scene load_scene(const SceneSource& src, bool quiet);

// The shipped graph a command draws when it is given none: tractography (every data file a
// TrackVis or MRtrix file by content) -> tracts_lineao (direction colours, whole lines), else
// variant1_lineao. Reads only the files' first bytes.
std::string default_graph(const SceneSource& src);
// default_graph, said on stderr when it is not the usual variant1_lineao (unless quiet).
std::string default_graph_noted(const SceneSource& src, bool quiet);

}  // namespace pathlet
