// What data to load and loading it: the data options of a command (common_options.hpp's
// SceneOptions), an experiment's data set and the Python module all name their data this way.
#pragma once

#include "io/pathline_io.hpp"

#include <pathlet/scene.hpp>

#include <string>

namespace pathlet {
struct TimeRange;
}

namespace pathlet::cli {

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

// A time the user gave that reaches outside the data's time span would render frames with
// nothing in them: InputError (exit 2) naming what was given and the data's span, unless
// `allow_empty` (--allow-empty-frames). Data without time takes any time.
void check_time_in_data(const TimeRange& t, const std::string& given, const Scene& scene, bool allow_empty);

}  // namespace pathlet::cli
