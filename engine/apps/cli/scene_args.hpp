// What data to load and loading it: the data options of a command (common_options.hpp's
// SceneOptions), an experiment's data set and the Python module all name their data this way.
#pragma once

#include <pathlet/scene.hpp>

#include <string>

namespace pathlet::cli {

struct SceneSource {
    std::string data;             // pathline file; "" = the built-in phantom
    std::string mesh;             // wall mesh file (optional)
    std::string phantom = "study";
    std::string time_array, velocity_array;
    double time_step = 0;         // text rows: seconds between samples (0: 0.01)
    std::string units;            // LENGTH[,VELOCITY] where the file does not say them (checked)
    bool streamlines = false;     // VTK lines without time or velocity load as lines drawn whole
    bool pseudo_time = false;     // lines without time animate along their arc length
};

// Loads what the source says; unless quiet, prints a one-line summary. Repair warnings go to
// stderr either way (a file that needed repairs should say so). A data set with no line left to
// draw after repair is a DataError naming the file and what the repair dropped.
Scene load_scene(const SceneSource& src, bool quiet);

}  // namespace pathlet::cli
