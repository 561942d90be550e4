// Scripted input for `pathlet view --script FILE.json` (tests, demos): events applied before a
// given shown frame, exactly as the keyboard and mouse would, with a fixed 1/25 s clock step.
//   [{"frame": 2, "key": "space"},                      space left right up down r l s ?
//    {"frame": 3, "drag": [40, 0], "button": "left"},   left: orbit, right/middle: pan
//    {"frame": 4, "scroll": 2},                          wheel steps, positive zooms in
//    {"frame": 5, "set": "lineao.strength=2"},           a parameter, as --set (the panels do this)
//    {"frame": 6, "graph": "graphs/isl.json"},           switch to another graph file
//    {"frame": 7, "reload": true}]                       load the graph file again (as after an edit)
#pragma once

#include <string>
#include <vector>

namespace pathlet::view {

struct ScriptEvent {
    long frame = 0;
    std::string key;     // one of the keys above, or empty
    std::string button;  // drag button: left, right, middle
    float dx = 0, dy = 0, scroll = 0;
    std::string set;     // NAME=VALUE
    std::string graph;   // switch to this graph file
    bool reload = false;
};

// Throws DataError naming the file and the JSON pointer of a bad event; the file is read with
// the limits of graph files (util/text.hpp: size, nesting, numbers).
std::vector<ScriptEvent> load_script(const std::string& path);
std::vector<ScriptEvent> parse_script(const std::string& text, const std::string& path);

}  // namespace pathlet::view
