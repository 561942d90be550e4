// Joining several data files into one set of pathlines, a bundle per file (scene_source.cpp).
#pragma once

#include <pathlet/scene.hpp>

#include <string>
#include <vector>

namespace pathlet {

struct LoadedBundle {
    std::string file;
    Pathlines lines;
};

// A bundle's name: its file's stem ("CST_left" for bundles/CST_left.tck).
std::string bundle_name(const std::string& file);

// The files' lines as one set, bundles numbered in name order (so the colours and the legend do
// not follow the arguments' order); the point arrays every file has; timeless lines share one
// pseudo-time speed. DataChoiceError for files of mixed kinds (with time and without).
Pathlines join_bundles(std::vector<LoadedBundle> parts);

}  // namespace pathlet
