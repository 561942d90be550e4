// The data options shared by commands that need a scene (render, bench):
// --data FILE (pathlines), --mesh FILE (vessel wall), --phantom PRESET (the default).
#pragma once

#include "args.hpp"

#include <pathlet/scene.hpp>

#include <string>

namespace pathlet::cli {

// What to load, as the options say it; also how an experiment's data set and the Python
// module name their data.
struct SceneSource {
    std::string data;             // pathline file; "" = the built-in phantom
    std::string mesh;             // wall mesh file (optional)
    std::string phantom = "study";
    std::string time_array, velocity_array;
    double time_step = 0;         // text rows: seconds between samples (0: 0.01)
    std::string units;            // --units LENGTH[,VELOCITY], where the file does not say them
    bool streamlines = false;     // VTK lines without time or velocity load as lines drawn whole
    bool pseudo_time = false;     // lines without time animate along their arc length
};

void add_scene_options(Args& a);
// --units checked (UsageError when malformed) and returned as given ("" when absent).
std::string units_option(const Args& a);
SceneSource scene_source(const Args& a);
// Loads what the source says; unless quiet, prints a one-line summary. Repair warnings go to
// stderr either way (a file that needed repairs should say so).
Scene load_scene(const SceneSource& src, bool quiet);
inline Scene load_scene(const Args& a, bool quiet) { return load_scene(scene_source(a), quiet); }

}  // namespace pathlet::cli
