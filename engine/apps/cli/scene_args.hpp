// The data options shared by commands that need a scene (render, bench):
// --data FILE (pathlines), --mesh FILE (vessel wall), --phantom PRESET (the default).
#pragma once

#include "args.hpp"

#include <pathlet/scene.hpp>

namespace pathlet::cli {

void add_scene_options(Args& a);
// --units checked (UsageError when malformed) and returned as given ("" when absent).
std::string units_option(const Args& a);
// Loads what the options say; prints a one-line summary and any repair warnings to stderr.
Scene load_scene(const Args& a, bool quiet);

}  // namespace pathlet::cli
