// What data to load and loading it: the data options of a command (cli's SceneOptions), an
// experiment's data set (bench) and the Python module all name their data this way.
#pragma once

#include "io/pathline_io.hpp"

#include <pathlet/scene.hpp>

#include <string>

namespace pathlet {

struct SceneSource {
    std::string data;             // pathline file; "" = the built-in phantom
    std::string mesh;             // wall mesh file (optional)
    std::string phantom = "study";
    io::LoadOptions load;         // arrays, time step, units, streamlines (units apply to the phantom too)
};

// Loads what the source says; unless quiet, prints a one-line summary. Repair warnings go to
// stderr either way (a file that needed repairs should say so). A data set with no line left to
// draw after repair is a DataError naming the file and what the repair dropped.
Scene load_scene(const SceneSource& src, bool quiet);

}  // namespace pathlet
